#pragma once
// Shared by the experiment tests: a quick run in a fresh temp folder, removed afterwards,
// and checks every paper-shaped report must pass.

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <string>

#include "tactile/experiments/experiment.h"

namespace tactile::test {

class ExperimentFolder {
 public:
  ExperimentFolder() {
    std::string pattern =
        (std::filesystem::temp_directory_path() / "tactile-experiment-test-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create " + pattern);
    path_ = pattern;
  }
  ~ExperimentFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ExperimentFolder(const ExperimentFolder&) = delete;
  ExperimentFolder& operator=(const ExperimentFolder&) = delete;
  std::string path() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

// Runs `name` with quick=true and seed 1 in a temp folder; counts progress calls.
inline experiments::ExperimentReport run_quick(const std::string& name, int* progress_calls) {
  ExperimentFolder folder;
  experiments::ExperimentOptions options;
  options.work_dir = folder.path();
  options.quick = true;
  options.seed = 1;
  options.progress = [progress_calls](const std::string& stage, int done, int total) {
    EXPECT_FALSE(stage.empty());
    EXPECT_LE(done, total);
    if (progress_calls) ++*progress_calls;
  };
  return experiments::run_experiment(name, options);
}

inline const experiments::ReportTable* find_table(const experiments::ExperimentReport& report,
                                                  const std::string& title_part) {
  for (const auto& table : report.tables)
    if (table.title.find(title_part) != std::string::npos) return &table;
  return nullptr;
}

}  // namespace tactile::test
