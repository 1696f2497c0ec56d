// The import that `tactile import` and the workbench share (formats/import.h): what it
// writes and reports, where it stops when asked to, and a preview that reads the same and
// writes nothing.
#include <gtest/gtest.h>

#include "io_test_files.h"
#include "tactile/error.h"
#include "tactile/formats/import.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labelstore/label_store.h"
#include "test_paths.h"

namespace tactile {
namespace {

const std::string kFixtures = test::test_data_dir() + "/import/";

FileImportOptions npz_options(const std::string& out) {
  FileImportOptions options;
  options.file = kFixtures + "frames.npz";
  options.layout = "grid:4x4";
  options.values.set("--rate", "100.0");
  options.values.set("--dataset", "pressure");
  options.values.set("--class-array", "gesture");
  options.out = out;
  return options;
}

FileImportOptions table_options(const std::string& out) {
  FileImportOptions options;
  options.file = kFixtures + "table.csv";
  options.layout = "strip:4";
  options.values.set("--class-column", "gesture");
  options.values.set("--group-columns", "subject,capture");
  options.out = out;
  return options;
}

TEST(ImportFiles, APreviewShowsTheFirstFramesAndTheClassesAndWritesNothing) {
  testing::TemporaryDirectory folder;
  FileImportOptions options = npz_options(folder.file("frames.h5"));
  options.labels = folder.file("labels.db");
  const ImportPreview preview = preview_import(options, 10);
  ASSERT_EQ(preview.refusal, "");
  EXPECT_EQ(preview.shape, (std::vector<int64_t>{50, 4, 4}));
  EXPECT_EQ(preview.channels.size(), 16u);
  EXPECT_EQ(preview.samples, 50);
  ASSERT_EQ(preview.frames.size(), 10u);
  EXPECT_DOUBLE_EQ(preview.times[3], 0.03);
  EXPECT_EQ(preview.classes, (std::vector<std::string>{"pat", "stroke"}));
  // The frames are the samples the import then writes.
  import_file(options);
  const Recording written = read_recording(folder.file("frames.h5"));
  for (size_t frame = 0; frame < 10; ++frame)
    for (size_t channel = 0; channel < 16; ++channel)
      EXPECT_EQ(preview.frames[frame][channel],
                written.streams.front().samples(static_cast<int64_t>(frame),
                                                static_cast<int64_t>(channel)));
  std::filesystem::remove(folder.file("frames.h5"));
  std::filesystem::remove_all(folder.file("labels.db"));
  preview_import(options, 10);
  EXPECT_EQ(folder.entry_count(), 0);
}

TEST(ImportFiles, ARefusalNamesTheOptionAsTheCommandLineDoes) {
  testing::TemporaryDirectory folder;
  FileImportOptions options = npz_options(folder.file("frames.h5"));
  options.values.erase("--rate");
  EXPECT_EQ(preview_import(options).refusal, "--rate: is needed for an array (it carries no time)");
  options = npz_options(folder.file("frames.h5"));
  options.values.set("--samples-per-capture", "3");
  // Another format's option, named with the options this one takes.
  EXPECT_EQ(preview_import(options).refusal,
            "--samples-per-capture: is not an option of NumPy files (theirs: --dataset, --rate, "
            "--class-array, --captures)");
  options = npz_options(folder.file("frames.h5"));
  options.layout.clear();
  EXPECT_NE(preview_import(options).refusal.find("--layout"), std::string::npos);
  EXPECT_THROW(import_file(options), Error);
  EXPECT_EQ(folder.entry_count(), 0);
}

TEST(ImportFiles, AGroupedImportReportsEachFileAndItsLabels) {
  testing::TemporaryDirectory folder;
  FileImportOptions options = table_options(folder.file("groups"));
  options.labels = folder.file("labels.db");
  std::vector<double> steps;
  std::vector<std::string> told;
  const FileImportReport report = import_file(
      options, [&steps](double fraction) { steps.push_back(fraction); },
      [&told](const ImportedFile& file) { told.push_back(file.recording); });
  ASSERT_EQ(report.files.size(), 4u);
  EXPECT_EQ(told,
            (std::vector<std::string>{"table-s1-1", "table-s1-2", "table-s2-1", "table-s2-2"}));
  EXPECT_EQ(report.labels, 4u);
  EXPECT_EQ(report.stored, 4u);
  EXPECT_EQ(
      imported_file_line(report.files.front()),
      "wrote " + folder.file("groups/table-s1-1.h5") +
          ": recording table-s1-1, layout strip:4, 20 samples x 4 channels at 100 Hz, 1 labels");
  EXPECT_TRUE(std::is_sorted(steps.begin(), steps.end()));
  EXPECT_EQ(steps.front(), 0.0);
  EXPECT_LT(steps.back(), 1.0);  // the last step is before the last file
  EXPECT_EQ(LabelStore(folder.file("labels.db")).list().size(), 4u);
}

TEST(ImportFiles, AStopBetweenFilesKeepsTheFilesWrittenBeforeIt) {
  testing::TemporaryDirectory folder;
  const FileImportOptions options = table_options(folder.file("groups"));
  struct Stop {};
  size_t written = 0;
  EXPECT_THROW(import_file(
                   options,
                   [&written](double) {
                     if (written == 2) throw Stop{};
                   },
                   [&written](const ImportedFile&) { ++written; }),
               Stop);
  EXPECT_EQ(written, 2u);
  EXPECT_TRUE(std::filesystem::exists(folder.file("groups/table-s1-2.h5")));
  EXPECT_FALSE(std::filesystem::exists(folder.file("groups/table-s2-1.h5")));
}

}  // namespace
}  // namespace tactile
