#pragma once
// The fixture shared by the LabelStore tests: a fresh directory per test.

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tactile/labelstore/label.h"
#include "temp_folder.h"

namespace tactile {

// A fresh directory per test, removed afterwards.
class LabelStoreTest : public ::testing::Test {
 protected:
  void SetUp() override { path_ = (directory_ / "labels.db").string(); }

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

  test::TempFolder folder_{"label_store"};
  std::filesystem::path directory_ = folder_.path();
  std::string path_;
};

}  // namespace tactile
