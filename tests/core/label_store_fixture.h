#pragma once
// The fixture shared by the LabelStore tests: a fresh directory per test.

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tactile/io/label.h"

namespace tactile {

// A fresh directory per test, removed afterwards.
class LabelStoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (std::filesystem::temp_directory_path() / "label_store_XXXXXX").string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    directory_ = pattern;
    path_ = (directory_ / "labels.db").string();
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }

  static Label make_label(const std::string& recording, double t0, double t1,
                          const std::string& class_name, const std::string& annotator = "ana") {
    Label label;
    label.recording = recording;
    label.t0 = t0;
    label.t1 = t1;
    label.class_name = class_name;
    label.annotator = annotator;
    return label;
  }

  static std::string read_text(const std::filesystem::path& path) {
    std::ifstream stream(path, std::ios::binary);
    std::stringstream text;
    text << stream.rdbuf();
    return text.str();
  }

  std::filesystem::path directory_;
  std::string path_;
};

}  // namespace tactile
