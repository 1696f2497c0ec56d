// `tactile import` of what other programs publish, end to end: NumPy .npy / .npz, JSON
// frames, another program's HDF5 dataset, classes per frame or capture, and one long CSV
// split into recordings by grouping columns, each read back with `tactile info` and
// `labels list`; bad input refused with the file and the place, and nothing written.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli_test_support.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labelstore/label_store.h"
#include "test_paths.h"

namespace tactile {
namespace {

using test::run_program;

const std::string kData = tactile::test::test_data_dir() + "/import/";

class ImportFormats : public ::testing::Test {
 protected:
  test::CommandResult import(const std::string& arguments) {
    return run_program("tactile", "import " + arguments, folder);
  }
  std::vector<Label> labels_of(const std::string& recording) {
    LabelStore store(folder.file("labels.db"));
    LabelFilter filter;
    filter.recording = recording;
    return store.list(filter);
  }
  test::TempFolder folder{"tactile-import-formats"};
};

TEST_F(ImportFormats, EachFormatWritesTheSameRecording) {
  const std::vector<std::string> inputs = {"frames.npy",
                                           "fortran.npy",
                                           "plain.npz --dataset pressure",
                                           "frames.npz --dataset pressure",
                                           "frames.json --key data.frames",
                                           "objects.json --key frames --value-key data",
                                           "foreign.h5 --dataset /sensors/pressure"};
  std::optional<Recording> first;
  for (size_t k = 0; k < inputs.size(); ++k) {
    const std::string out = folder.file("r" + std::to_string(k) + ".h5");
    const auto result = import(kData + inputs[k] + " --layout grid:4x4 --rate 100 --out " + out);
    ASSERT_EQ(result.exit_code, 0) << inputs[k] << ": " << result.err;
    Recording recording = read_recording(out);
    ASSERT_EQ(recording.streams.front().sample_count(), 50) << inputs[k];
    if (!first) {
      first = std::move(recording);
    } else {
      EXPECT_TRUE(recording.streams.front().samples.isApprox(first->streams.front().samples, 1e-6))
          << inputs[k];
    }
  }
}

TEST_F(ImportFormats, ClassesPerFrameBecomeGroundTruthLabels) {
  for (const std::string input :
       {"frames.npz --dataset pressure --class-array gesture",
        "frames.json --key data.frames --class-array data.gesture",
        "objects.json --key frames --value-key data --class-key label",
        "foreign.h5 --dataset /sensors/pressure --class-array /sensors/gesture"}) {
    const auto result = import(kData + input + " --layout grid:4x4 --rate 100 --out " +
                               folder.file("g.h5") + " --labels " + folder.file("labels.db"));
    ASSERT_EQ(result.exit_code, 0) << input << ": " << result.err;
    const std::vector<Label> labels = labels_of("g");
    ASSERT_EQ(labels.size(), 2u) << input << " (importing again replaces, never doubles)";
    EXPECT_EQ(labels[0].class_name, "pat");
    EXPECT_EQ(labels[1].class_name, "stroke");
  }
  const auto captures =
      import(kData +
             "caps.npz --dataset x --captures --class-array y --layout grid:4x4 --rate 100 --out " +
             folder.file("c.h5") + " --labels " + folder.file("labels.db"));
  ASSERT_EQ(captures.exit_code, 0) << captures.err;
  EXPECT_EQ(labels_of("c").size(), 6u);
}

TEST_F(ImportFormats, OneTableSplitsIntoRecordingsByItsGroupingColumns) {
  const auto result = import(
      kData +
      "table.csv --layout strip:4 --class-column gesture --group-columns subject,capture --out " +
      folder.file("groups") + " --labels " + folder.file("labels.db"));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  for (const std::string id : {"table-s1-1", "table-s1-2", "table-s2-1", "table-s2-2"}) {
    const RecordingFile file(folder.file("groups/" + id + ".h5"));
    EXPECT_EQ(file.stream("skin").sample_count, 20);
    EXPECT_EQ(file.metadata().at("subject"), id.substr(6, 2));
    ASSERT_EQ(labels_of(id).size(), 1u) << id;
  }
  // Again: the files exist, and nothing is written over them.
  const auto again = import(
      kData +
      "table.csv --layout strip:4 --class-column gesture --group-columns subject,capture --out " +
      folder.file("groups"));
  EXPECT_NE(again.exit_code, 0);
  EXPECT_NE(again.err.find("exists already"), std::string::npos) << again.err;
}

TEST_F(ImportFormats, BadInputIsRefusedWithItsPlaceAndWritesNothing) {
  const std::string out = folder.file("never.h5");
  const std::vector<test::RefusedImport> cases = {
      {kData + "frames.npy --layout grid:4x5 --rate 10", "does not fit grid:4x5"},
      {kData + "frames.npy --layout grid:4x4", "--rate"},
      {kData + "frames.npz --layout grid:4x4 --rate 10",
       "holds 2 arrays (pressure, gesture): name one"},
      {kData + "frames.npz --layout grid:4x4 --rate 10 --dataset force", "no array 'force'"},
      {kData + "frames.json --layout grid:4x4 --rate 10 --key data.nothing",
       "no key 'data.nothing'"},
      {kData + "foreign.h5 --layout grid:4x4 --rate 10",
       "to read (it holds /sensors/gesture 50 string, /sensors/pressure 50x4x4 float32)"},
      {kData + "frames.npz --layout grid:4x4 --rate 10 --dataset pressure --class-array pressure",
       "800 classes for 50 frames"},
      {kData + "table.csv --layout strip:4 --class-column kind", "no column 'kind'"},
      {kData + "frames.npy --layout grid:4x4 --rate 10 --class-column x", "--class-array"},
      {kData + "frames.npz --layout grid:4x4 --rate 10 --dataset pressure --class-column gesture",
       "--class-column: is for CSV tables; the classes of an array file are named by "
       "--class-array"},
      {kData + "objects.json --layout grid:4x4 --rate 10 --key frames",
       "holds objects, not arrays: name the member of each that holds its frame (--value-key)"},
      {kData + "objects.json --layout grid:4x4 --rate 10 --key frames --value-key pressure",
       "[0]: no member 'pressure'"},
  };
  test::expect_imports_refused(cases, out, folder);
}

}  // namespace
}  // namespace tactile
