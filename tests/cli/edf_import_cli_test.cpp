// `tactile import FILE.edf|FILE.bdf` end to end on files EDFlib wrote: the recording and its
// annotations as ground truth (or as an annotator's labels with --annotator), `tactile verify`
// on what was written, and bad flags and bad files refused with the clear error, writing nothing.
#include <gtest/gtest.h>

#include <filesystem>

#include "cli_test_support.h"
#include "edf_test_files.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labelstore/label_store.h"

namespace tactile {
namespace {

using test::run_program;

class EdfImportCli : public ::testing::Test {
 protected:
  void SetUp() override {
    testing::write_edf_test_file(edf, testing::edf_test_plus_file());
    testing::write_edf_test_file(bdf, testing::edf_test_bdf_file());
  }
  test::CommandResult tactile(const std::string& arguments) {
    return run_program("tactile", arguments, folder);
  }
  std::vector<Label> labels_of(const std::string& annotator) {
    LabelStore store(folder.file("labels.db"));
    LabelFilter filter;
    filter.annotator = annotator;
    return store.list(filter);
  }
  test::TempFolder folder{"tactile-edf-cli"};
  std::string edf = folder.file("session.edf"), bdf = folder.file("press.bdf");
  std::string four = " --layout strip:4 --signals Fz,Cz,Pz,Oz --annotation-seconds 0.5";
};

TEST_F(EdfImportCli, ImportWritesTheRecordingAndTheAnnotationsAsGroundTruth) {
  const std::string out = folder.file("s.h5");
  const auto result =
      tactile("import " + edf + four + " --out " + out + " --labels " + folder.file("labels.db"));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find(
                "wrote " + out +
                ": recording s, layout strip:4, 300 samples x 4 channels at 100 Hz, 3 labels"),
            std::string::npos)
      << result.out;
  EXPECT_NE(result.out.find("stored 3 ground-truth labels"), std::string::npos) << result.out;
  const Recording recording = read_recording(out);
  const Stream& stream = recording.streams.front();
  const testing::EdfTestFile spec = testing::edf_test_plus_file();
  for (int64_t row : {0, 1, 150, 299})
    EXPECT_NEAR(stream.samples(row, 2), testing::edf_test_value(spec.signals[2], 2, row), 1e-4)
        << row;
  EXPECT_EQ(stream.units.front(), "uV");
  EXPECT_EQ(recording.metadata.at("edf_signals"), "Fz,Cz,Pz,Oz");
  const std::vector<Label> truth = labels_of("import");
  ASSERT_EQ(truth.size(), 3u);
  EXPECT_EQ(truth[1].class_name, "Stroke");
  EXPECT_EQ(truth[1].recording, "s");
  const auto verify = tactile("verify " + out);
  EXPECT_EQ(verify.exit_code, 0) << verify.out << verify.err;
}

// EDFbrowser closes a file with "Recording ends" at its last instant: no label is made of it,
// and the import's line says so instead of leaving it to `tactile info`.
TEST_F(EdfImportCli, AnAnnotationAtTheEndIsNamedAsNoLabelInTheImportsLine) {
  testing::EdfTestFile spec = testing::edf_test_plus_file();
  spec.annotations = {{0.5, 0.25, "Tap"}, {3.0, -1.0, "Recording ends"}};
  testing::write_edf_test_file(edf, spec);
  const std::string out = folder.file("ends.h5");
  const auto result = tactile("import " + edf + four + " --out " + out);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find(", 1 labels; no label made of: annotation 2 at 3 s \"Recording "
                            "ends\": at or after the data's end (3 s)"),
            std::string::npos)
      << result.out;
}

TEST_F(EdfImportCli, AnnotatorStoresTheLabelsAsThatPersonsAndASecondImportReplacesThem) {
  const std::string arguments = "import " + bdf + " --layout strip:2 --annotator maria --out " +
                                folder.file("p.h5") + " --labels " + folder.file("labels.db");
  for (int round = 0; round < 2; ++round) {
    const auto result = tactile(arguments);
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.out.find("stored 2 labels of maria"), std::string::npos) << result.out;
  }
  const std::vector<Label> labels = labels_of("maria");
  ASSERT_EQ(labels.size(), 2u);
  EXPECT_EQ(labels[0].class_name, "Press");
  EXPECT_EQ(labels[0].source, LabelSource::kManual);
  EXPECT_TRUE(labels_of("import").empty()) << "no ground truth written";
  EXPECT_EQ(tactile("verify " + folder.file("p.h5")).exit_code, 0);
}

TEST_F(EdfImportCli, BadFlagsAndBadFilesAreRefusedClearlyAndWriteNothing) {
  const std::string out = folder.file("never.h5");
  std::filesystem::copy_file(edf, folder.file("cut.edf"));
  std::filesystem::resize_file(folder.file("cut.edf"), std::filesystem::file_size(edf) - 100);
  const std::vector<test::RefusedImport> cases = {
      {edf + " --layout strip:5", "\"Resp\" 25 Hz"},
      {edf + " --layout strip:4 --signals Fz,Cz,Pz,T3", "--signals: no signal \"T3\" in"},
      {edf + " --layout strip:3 --signals Fz,Cz,Pz,Oz",
       "4 signals (Fz, Cz, Pz, Oz) do not fit strip:3's 3 channels"},
      {edf + " --layout strip:4 --signals Fz,Cz,Pz,Oz",
       "annotation 3 at 2 s \"Pat\": has no duration"},
      {edf + four + " --rate 100", "--rate: an EDF or BDF file states its own rate"},
      {edf + four + " --annotation-seconds 0", "--annotation-seconds"},
      {edf + four + " --dataset x", "--dataset: is not for EDF or BDF files"},
      {folder.file("cut.edf") + four, "byte 236: 3 data records of"},
      {folder.file("missing.edf") + four, "missing.edf"},
  };
  test::expect_imports_refused(cases, out, folder);
}

}  // namespace
}  // namespace tactile
