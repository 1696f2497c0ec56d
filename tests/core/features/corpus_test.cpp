// Corpus extraction: rows in the given order whatever the threads do, classes of
// segmenter segments from the ground truth, errors naming the file.
#include "tactile/features/corpus.h"

#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>

#include "io_test_files.h"
#include "tactile/error.h"
#include "tactile/features/generic.h"
#include "tactile/io/hdf5_file.h"

namespace tactile {
namespace {

Label make_label(const std::string& recording, double t0, double t1, const std::string& name,
                 int64_t id) {
  Label label;
  label.id = id;
  label.recording = recording;
  label.t0 = t0;
  label.t1 = t1;
  label.class_name = name;
  return label;
}

class CorpusTest : public ::testing::Test {
 protected:
  // A folder of this process's own: another test run on the machine may run the same test.
  void SetUp() override { folder_ = directory_.path(); }

  // A strip recording whose channel 0 holds the recording's number everywhere, so each
  // row shows which recording it came from.
  CorpusRecording write(int number, const std::string& layout_id = "strip:2") {
    const SkinLayout layout = load_layout(layout_id);
    Recording recording;
    recording.id = "r" + std::to_string(number);
    recording.layout_id = layout.id;
    recording.metadata = {{"subject", "s" + std::to_string(number % 3)}};
    Stream stream;
    stream.name = "skin";
    stream.rate_hz = 10.0;
    for (const Channel& channel : layout.channels) stream.channels.push_back(channel.name);
    stream.units.assign(layout.channels.size(), "");
    stream.samples = SampleMatrix::Zero(50, static_cast<int64_t>(layout.channels.size()));
    stream.samples.col(0).setConstant(static_cast<float>(number));
    recording.streams.push_back(std::move(stream));
    CorpusRecording job;
    job.id = recording.id;
    job.path = (folder_ / (recording.id + ".h5")).string();
    write_recording(job.path, recording);
    job.segments = {make_label(job.id, 0.0, 1.0, "a", number * 10 + 1),
                    make_label(job.id, 2.0, 3.0, "b", number * 10 + 2)};
    return job;
  }

  tactile::testing::TemporaryDirectory directory_;
  std::filesystem::path folder_;
};

TEST_F(CorpusTest, RowsFollowTheGivenOrderOnAnyNumberOfThreads) {
  std::vector<CorpusRecording> jobs;
  for (int number = 1; number <= 7; ++number) jobs.push_back(write(number));
  const auto extractor = make_generic_extractor({});
  int64_t calls = 0, last_done = 0;
  CorpusOptions options;
  options.threads = 3;
  options.progress = [&](int64_t done, int64_t total) {
    ++calls;
    EXPECT_EQ(total, 7);
    EXPECT_EQ(done, last_done + 1);
    last_done = done;
  };
  const CorpusDataset corpus = extract_corpus(*extractor, jobs, options);
  EXPECT_EQ(calls, 7);
  ASSERT_EQ(corpus.dataset.rows(), 14);
  EXPECT_EQ(corpus.segments, 14);
  for (int64_t row = 0; row < 14; ++row) {
    const int number = static_cast<int>(row / 2) + 1;
    EXPECT_EQ(corpus.dataset.features(row, 3), number);  // ch0.peak
    EXPECT_EQ(corpus.dataset.recordings[row], std::string("r").append(std::to_string(number)));
    EXPECT_EQ(corpus.dataset.segment_ids[row], number * 10 + 1 + row % 2);
    EXPECT_EQ(corpus.dataset.subjects[row], std::string("s").append(std::to_string(number % 3)));
  }
  EXPECT_EQ(corpus.dataset.metadata[1].at("t0"), "2");
  EXPECT_EQ(corpus.dataset.metadata[1].at("region"), "all");
}

TEST_F(CorpusTest, ALayoutWithOtherColumnsIsAnErrorNamingTheFile) {
  std::vector<CorpusRecording> jobs = {write(1), write(2, "strip:3")};
  try {
    extract_corpus(*make_generic_extractor({}), jobs, {});
    FAIL() << "mixed layouts accepted";
  } catch (const Error& error) {
    EXPECT_NE(error.where().find("r2.h5"), std::string::npos) << error.what();
  }
}

TEST_F(CorpusTest, UnreadableRecordingNamesItsFile) {
  std::vector<CorpusRecording> jobs = {write(1), write(2)};
  jobs[1].path = (folder_ / "absent.h5").string();
  EXPECT_THROW(extract_corpus(*make_generic_extractor({}), jobs, {}), Error);
}

TEST_F(CorpusTest, CancelStopsWithAnError) {
  std::vector<CorpusRecording> jobs = {write(1)};
  const std::atomic<bool> cancel{true};
  CorpusOptions options;
  options.cancel = &cancel;
  EXPECT_THROW(extract_corpus(*make_generic_extractor({}), jobs, options), Error);
}

TEST(SegmentClass, UnknownSegmentsTakeTheLongestOverlappingGroundTruth) {
  const std::vector<Label> truth = {make_label("r", 0.0, 1.0, "pat", 1),
                                    make_label("r", 1.0, 3.0, "stroke", 2),
                                    make_label("other", 0.0, 9.0, "slap", 3)};
  EXPECT_EQ(segment_class(make_label("r", 0.5, 1.6, kUnknownClass, 9), truth), "stroke");
  EXPECT_EQ(segment_class(make_label("r", 0.2, 1.5, "", 9), truth), "pat");
  EXPECT_EQ(segment_class(make_label("r", 5.0, 6.0, "", 9), truth), kUnknownClass);
  EXPECT_EQ(segment_class(make_label("r", 0.5, 1.6, "poke", 9), truth), "poke");
}

}  // namespace
}  // namespace tactile
