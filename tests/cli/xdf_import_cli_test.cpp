// `tactile import FILE.xdf` end to end: the glove session of tests/data/interop (a data stream
// with a dropout, a markers stream, clock offsets) written as a recording and its
// ground-truth labels, `tactile verify` on it, the stream chosen by name or type, and bad
// flags and damaged files refused with the place and nothing written.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "cli_test_support.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labelstore/label_store.h"
#include "test_paths.h"

namespace tactile {
namespace {

using test::run_program;

const std::string kSession = tactile::test::test_data_dir() + "/interop/glove_session.xdf";

class XdfImportCli : public ::testing::Test {
 protected:
  test::CommandResult tactile(const std::string& arguments) {
    return run_program("tactile", arguments, folder);
  }
  test::TempFolder folder{"tactile-xdf-import"};
};

TEST_F(XdfImportCli, TheSessionBecomesARecordingAndItsMarkersGroundTruthLabels) {
  const std::string out = folder.file("glove.h5"), labels = folder.file("labels.db");
  const auto result =
      tactile("import " + kSession + " --layout strip:8 --out " + out + " --labels " + labels);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("wrote " + out +
                            ": recording glove, layout strip:8, 60 samples x 8 channels at 100 "
                            "Hz, 4 labels"),
            std::string::npos)
      << result.out;
  const Recording recording = read_recording(out);
  const Stream& stream = recording.streams.front();
  ASSERT_EQ(stream.sample_count(), 60);
  EXPECT_EQ(stream.samples(0, 3), 300.25f);
  EXPECT_TRUE(std::isnan(stream.samples(33, 3)));  // the dropout stays a gap
  EXPECT_EQ(recording.metadata.at("xdf_stream"), "TactileGlove");
  LabelStore store(labels);
  LabelFilter filter;
  filter.recording = "glove";
  const std::vector<Label> stored = store.list(filter);
  ASSERT_EQ(stored.size(), 4u);
  EXPECT_EQ(stored[1].class_name, "pat");
  EXPECT_NEAR(stored[1].t0, 0.302, 1e-6);
  EXPECT_EQ(stored[1].source, LabelSource::kGroundTruth);
  const auto verified = tactile("verify " + out);
  EXPECT_EQ(verified.exit_code, 0) << verified.out << verified.err;
  // Importing again replaces the ground truth, never doubles it.
  ASSERT_EQ(tactile("import " + kSession +
                    " --layout strip:8 --stream type:Tactile --markers Touches --out " +
                    folder.file("again.h5") + " --recording-id glove --labels " + labels)
                .exit_code,
            0);
  EXPECT_EQ(store.list(filter).size(), 4u);
}

TEST_F(XdfImportCli, BadFlagsAndDamagedFilesAreRefusedWithThePlaceAndWriteNothing) {
  const std::string out = folder.file("never.h5");
  // The session cut inside its last chunk, as a recorder that died would leave it.
  const std::string bytes = test::read_text(kSession);
  const std::string cut = folder.file("cut.xdf");
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() - 10);
  const std::vector<test::RefusedImport> cases = {
      {kSession + " --layout strip:8 --rate 50",
       "--rate: an XDF stream is resampled to its own nominal rate"},
      {kSession + " --layout strip:4",
       "stream \"TactileGlove\": has 8 channels, layout strip:4 has 4"},
      {kSession + " --layout strip:8 --stream Wrist",
       "--stream: " + kSession +
           " has no 'Wrist' among its numeric streams; its streams:\n  \"TactileGlove\""},
      {kSession + " --layout strip:8 --markers type:Events", "--markers: "},
      {kSession + " --layout strip:8 --dataset x", "--dataset: is not for XDF files"},
      {tactile::test::test_data_dir() + "/import/frames.npy --layout grid:4x4 --rate 10 --stream x",
       "--stream: is not an option of NumPy files"},
      {cut + " --layout strip:8", "cut.xdf chunk 15 at byte "},
  };
  test::expect_imports_refused(cases, out, folder);
}

}  // namespace
}  // namespace tactile
