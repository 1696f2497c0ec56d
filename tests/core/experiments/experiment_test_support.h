#pragma once
// Shared by the experiment tests: a quick run in a fresh temp folder, removed afterwards,
// and checks every paper-shaped report must pass.

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <string>

#include "tactile/experiments/experiment.h"
#include "temp_folder.h"

namespace tactile::test {

// An experiment's work folder: the shared temporary folder (tests/support/temp_folder.h).
struct ExperimentFolder : TempFolder {
  ExperimentFolder() : TempFolder("tactile-experiment-test") {}
  std::string work_dir() const { return path().string(); }
};

// Runs `name` with quick=true and seed 1 in a temp folder; counts progress calls.
inline experiments::ExperimentReport run_quick(const std::string& name, int* progress_calls) {
  ExperimentFolder folder;
  experiments::ExperimentOptions options;
  options.work_dir = folder.work_dir();
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
