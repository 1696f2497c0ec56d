// The label formats behind `labels export` / `labels import` (labels/label_format.h): one list,
// a file found by its extension and, where two formats share one, by its shape; each format
// reads back what it writes.
#include "tactile/labels/label_format.h"

#include <gtest/gtest.h>

#include <fstream>

#include "tactile/error.h"
#include "temp_folder.h"

namespace tactile {
namespace {

std::vector<Label> two_labels() {
  Label a;
  a.recording = "r1";
  a.t0 = 1.0;
  a.t1 = 2.5;
  a.region = "all";
  a.class_name = "tap";
  a.annotator = "ana";
  a.source = LabelSource::kManual;
  Label b = a;
  b.t0 = 3.0;
  b.t1 = 4.0;
  b.class_name = "stroke";
  return {a, b};
}

TEST(LabelFormats, AreOursThenOtherToolsEachWithItsExportFlag) {
  std::vector<std::string> names, flags;
  for (const LabelFormat* format : label_formats()) {
    names.push_back(format->name());
    flags.push_back(format->flag());
  }
  EXPECT_EQ(names, (std::vector<std::string>{"CSV", "JSON", "ELAN", "Label Studio"}));
  EXPECT_EQ(flags, (std::vector<std::string>{"--csv", "--json", "--eaf", "--label-studio"}));
  EXPECT_TRUE(label_format_named("ELAN")->one_recording());
  EXPECT_FALSE(label_format_named("CSV")->one_recording());
  EXPECT_EQ(label_format_named("Praat"), nullptr);
}

TEST(LabelFormats, ReadBackWhatTheyWriteAndTellTheTwoJsonShapesApart) {
  const test::TempFolder folder("tactile-label-formats");
  for (const LabelFormat* format : label_formats()) {
    SCOPED_TRACE(format->name());
    const std::string path =
        folder.file("labels-" + std::to_string(format->flag().size()) + format->extension());
    std::ofstream(path, std::ios::binary) << format->write(two_labels(), {"tap", "stroke"}, {});
    // The file is recognised as this format, and its labels come back.
    EXPECT_EQ(&label_format_of(path), format);
    std::vector<std::string> left_out;
    const std::vector<Label> read = format->read(path, {}, left_out);
    EXPECT_TRUE(left_out.empty());
    ASSERT_EQ(read.size(), 2u);
    EXPECT_EQ(read[0].class_name, "tap");
    EXPECT_EQ(read[1].class_name, "stroke");
    EXPECT_DOUBLE_EQ(read[1].t0, 3.0);
  }
  // One recording per ELAN document.
  std::vector<Label> labels = two_labels();
  labels[1].recording = "r2";
  EXPECT_NE(test::refusal_of([&] {
              label_format_named("ELAN")->write(labels, {}, {});
            }).find("--recording: one .eaf holds one recording"),
            std::string::npos);
  std::ofstream(folder.file("notes.txt")) << "x";
  EXPECT_NE(test::refusal_of([&] {
              label_format_of(folder.file("notes.txt"));
            }).find("not a label file import reads: CSV (.csv), JSON (.json), ELAN (.eaf)"),
            std::string::npos);
}

}  // namespace
}  // namespace tactile
