// Features and predictions read from a recording file (the workbench's Predict): a pipeline
// that reads only each segment's samples reads their windows alone, and gives the values and
// answers of the whole recording held in memory; any other pipeline reads the stream once.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "io_test_files.h"
#include "tactile/features/corpus.h"
#include "tactile/features/feature_extractor.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labels/predict.h"
#include "tactile/sim/simulator.h"
#include "tactile/skins/skin.h"

namespace tactile {
namespace {

struct Trial {
  SkinLayout layout;
  SimulatedTrial trial;
  std::string path;
};

Trial simulated(const std::string& skin, const testing::TemporaryDirectory& folder) {
  Trial made;
  made.layout = load_layout(skin);
  SimulationOptions options;
  options.subjects = 1;
  options.repetitions = 2;
  made.trial = skin_record(skin).simulate(made.layout, options, 0, 0);
  made.path = folder.file(skin + ".h5");
  write_recording(made.path, made.trial.recording);
  return made;
}

// Every segment's values (or reason to skip) the same, bit for bit.
void expect_same(const FeatureExtractor::Segments& read, const FeatureExtractor::Segments& whole) {
  ASSERT_EQ(read.results.size(), whole.results.size());
  for (size_t k = 0; k < whole.results.size(); ++k) {
    EXPECT_EQ(read.results[k].skip_reason, whole.results[k].skip_reason) << "segment " << k;
    EXPECT_EQ(read.results[k].values, whole.results[k].values) << "segment " << k;
  }
}

TEST(PredictFromASource, RobovieSegmentsReadAloneGiveTheWholeRecordingsFeatures) {
  const testing::TemporaryDirectory folder;
  const Trial robovie = simulated("robovie", folder);
  const auto extractor = make_feature_extractor(default_pipeline("robovie"), {});
  ASSERT_TRUE(extractor->reads_segment_only());
  FileSourceOptions small;
  small.cache_bytes = 1 << 20;
  const FileSampleSource source(robovie.path, small);
  std::vector<Label> segments = robovie.trial.labels;
  ASSERT_GE(segments.size(), 4u);
  // A segment past the end and one of a single sample: skipped alike.
  Label beyond = segments.back();
  beyond.t0 = source.end_time() + 1.0;
  beyond.t1 = beyond.t0 + 1.0;
  Label short_one = segments.front();
  short_one.t1 = short_one.t0 + 0.5 / source.rate_hz();
  segments.push_back(beyond);
  segments.push_back(short_one);
  size_t calls = 0;
  const FeatureExtractor::Segments read = extract_source_segments(
      *extractor, source, robovie.layout, segments, [&](size_t) { ++calls; });
  expect_same(read, extractor->extract_segments(robovie.trial.recording, robovie.layout, segments));
  EXPECT_EQ(calls, segments.size());
  EXPECT_FALSE(read.results[segments.size() - 1].skip_reason.empty());
  EXPECT_FALSE(read.results[segments.size() - 2].skip_reason.empty());

  // And the model's answers: fitted on the trial's own rows, asked from the file.
  Dataset table;
  const std::vector<FeatureColumn> columns = extractor->columns(robovie.layout);
  for (const FeatureColumn& column : columns) table.columns.push_back(column);
  const FeatureExtractor::Segments rows =
      extractor->extract_segments(robovie.trial.recording, robovie.layout, robovie.trial.labels);
  table.features.resize(static_cast<Eigen::Index>(rows.results.size()),
                        static_cast<Eigen::Index>(columns.size()));
  for (size_t row = 0; row < rows.results.size(); ++row) {
    ASSERT_TRUE(rows.results[row].skip_reason.empty());
    for (size_t column = 0; column < columns.size(); ++column)
      table.features(static_cast<Eigen::Index>(row), static_cast<Eigen::Index>(column)) =
          rows.results[row].values[column];
    table.classes.push_back(robovie.trial.labels[row].class_name);
    table.subjects.push_back("s1");
    table.recordings.push_back(robovie.trial.recording.id);
    table.segment_ids.push_back(static_cast<int64_t>(row + 1));
    table.metadata.push_back({{"layout", "robovie"}});
  }
  const SavedModel model = model_from_json(
      fit_model_document(table, "knn:k=1", 1, default_pipeline("robovie")), "test model");
  const Predictions from_file = predict_segments(model, source, robovie.layout, segments);
  const Predictions in_memory =
      predict_segments(model, robovie.trial.recording, robovie.layout, segments);
  ASSERT_EQ(from_file.labels.size(), in_memory.labels.size());
  EXPECT_EQ(from_file.skipped.size(), 2u);
  for (size_t k = 0; k < in_memory.labels.size(); ++k) {
    EXPECT_EQ(from_file.labels[k].class_name, in_memory.labels[k].class_name);
    EXPECT_EQ(from_file.labels[k].confidence, in_memory.labels[k].confidence);
    EXPECT_EQ(from_file.labels[k].t0, in_memory.labels[k].t0);
    EXPECT_EQ(from_file.labels[k].recording, robovie.trial.recording.id);
  }

  // The model as fitted (the workbench keeps it after training, and Predict reads no file)
  // answers as its document read back does, to the last bit of every score.
  const SavedModel fitted = fit_model(table, "linear-svm", 1, default_pipeline("robovie"));
  const SavedModel read_back = model_from_json(model_document(fitted), "test model");
  EXPECT_EQ(read_back.features, fitted.features);
  EXPECT_EQ(read_back.pipeline_params, fitted.pipeline_params);
  EXPECT_EQ(read_back.layout, "robovie");
  const Predictions fitted_answers = predict_segments(fitted, source, robovie.layout, segments);
  const Predictions read_answers = predict_segments(read_back, source, robovie.layout, segments);
  ASSERT_EQ(fitted_answers.labels.size(), read_answers.labels.size());
  for (size_t k = 0; k < fitted_answers.labels.size(); ++k) {
    EXPECT_EQ(fitted_answers.labels[k].class_name, read_answers.labels[k].class_name);
    EXPECT_EQ(fitted_answers.labels[k].confidence, read_answers.labels[k].confidence);
    EXPECT_EQ(fitted_answers.labels[k].note, read_answers.labels[k].note);
  }
}

// Training reads the same way: a corpus of a file gives the rows of the recording in memory.
TEST(PredictFromASource, ACorpusOfRobovieReadsTheSegmentsWindowsAndGivesTheSameRows) {
  const testing::TemporaryDirectory folder;
  const Trial robovie = simulated("robovie", folder);
  const auto extractor = make_feature_extractor(default_pipeline("robovie"), {});
  CorpusRecording job;
  job.id = robovie.trial.recording.id;
  job.path = robovie.path;
  job.segments = robovie.trial.labels;
  job.ground_truth = robovie.trial.labels;
  const CorpusDataset corpus = extract_corpus(*extractor, {job});
  const FeatureExtractor::Segments whole =
      extractor->extract_segments(robovie.trial.recording, robovie.layout, robovie.trial.labels);
  ASSERT_EQ(corpus.dataset.rows(), static_cast<Eigen::Index>(whole.results.size()));
  for (size_t row = 0; row < whole.results.size(); ++row)
    for (size_t column = 0; column < whole.results[row].values.size(); ++column)
      ASSERT_EQ(corpus.dataset.features(static_cast<Eigen::Index>(row),
                                        static_cast<Eigen::Index>(column)),
                whole.results[row].values[column]);
}

TEST(PredictFromASource, APipelineThatPreprocessesReadsTheWholeStream) {
  const testing::TemporaryDirectory folder;
  const Trial fur = simulated("fur", folder);
  const auto extractor = make_feature_extractor(default_pipeline("fur"), {});
  ASSERT_FALSE(extractor->reads_segment_only());
  const FileSampleSource source(fur.path);
  std::vector<double> shares;
  const FeatureExtractor::Segments read =
      extract_source_segments(*extractor, source, fur.layout, fur.trial.labels, {},
                              [&](double share) { shares.push_back(share); });
  expect_same(read, extractor->extract_segments(fur.trial.recording, fur.layout, fur.trial.labels));
  ASSERT_FALSE(shares.empty());
  EXPECT_DOUBLE_EQ(shares.back(), 1.0);
}

}  // namespace
}  // namespace tactile
