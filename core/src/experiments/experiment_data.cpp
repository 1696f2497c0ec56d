#include "experiment_data.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>

#include "tactile/error.h"
#include "tactile/features/corpus.h"
#include "tactile/features/feature_extractor.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/segment/segmenter.h"
#include "tactile/skins/workspace.h"

namespace tactile::experiments {

void report_progress(const ExperimentOptions& options, const std::string& stage, int done,
                     int total) {
  if (options.progress) options.progress(stage, done, total);
}

Dataset experiment_dataset(const ExperimentOptions& options, const std::string& skin,
                           const SimulationOptions& simulation, const std::string& pipeline,
                           const std::string& segmenter) {
  std::filesystem::path folder;
  if (options.data_dir.empty()) {
    if (options.work_dir.empty())
      throw Error("work folder",
                  "an experiment without --data needs a work folder to simulate into");
    folder = std::filesystem::path(options.work_dir) / skin;
    write_simulation(folder.string(), skin, simulation, [&options](int done, int total) {
      report_progress(options, "simulate", done, total);
    });
  } else {
    folder = options.data_dir;
  }
  const std::string database = (folder / "labels.db").string();
  if (!std::filesystem::is_regular_file(database))
    throw Error(database, "no label database (the experiment needs ground-truth labels)");
  LabelStore store(database, LabelStore::OpenMode::kExisting);
  LabelFilter filter;
  filter.source = LabelSource::kGroundTruth;
  const std::vector<Label> labels = store.list(filter);
  if (labels.empty()) throw Error(database, "no ground-truth labels");
  std::map<std::string, size_t> index;
  std::vector<CorpusRecording> recordings;
  for (const Label& label : labels) {
    auto found = index.find(label.recording);
    if (found == index.end()) {
      CorpusRecording recording;
      recording.id = label.recording;
      recording.path = (folder / (label.recording + ".h5")).string();
      if (!std::filesystem::is_regular_file(recording.path))
        throw Error(recording.path, "recording file missing (it has labels in " + database + ")");
      found = index.emplace(label.recording, recordings.size()).first;
      recordings.push_back(std::move(recording));
    }
    recordings[found->second].segments.push_back(label);
    recordings[found->second].ground_truth.push_back(label);
  }
  if (!segmenter.empty()) {
    // The papers cut their gestures with these segmenters; the simulator's ground truth
    // only names the class of each segment found.
    int done = 0;
    for (CorpusRecording& recording : recordings) {
      const Recording samples = read_recording(recording.path);
      std::vector<Label> found =
          segment_recording(segmenter, samples, load_layout(samples.layout_id));
      recording.segments.clear();
      for (Label& segment : found) {
        segment.recording = recording.id;
        segment.class_name = segment_class(segment, recording.ground_truth);
        if (segment.class_name != kUnknownClass) recording.segments.push_back(std::move(segment));
      }
      report_progress(options, "segment", ++done, static_cast<int>(recordings.size()));
    }
  }
  const auto extractor = make_feature_extractor(pipeline);
  CorpusOptions corpus_options;
  corpus_options.progress = [&options](int64_t done, int64_t total) {
    report_progress(options, "features", static_cast<int>(done), static_cast<int>(total));
  };
  CorpusDataset corpus = extract_corpus(*extractor, recordings, corpus_options);
  if (corpus.dataset.rows() == 0)
    throw Error(database, "no feature rows: all " + std::to_string(corpus.segments) +
                              " segments were skipped");
  return std::move(corpus.dataset);
}

std::vector<int> class_indices(const Dataset& dataset, const std::vector<std::string>& classes) {
  std::map<std::string, int> index;
  for (size_t k = 0; k < classes.size(); ++k) index[classes[k]] = static_cast<int>(k);
  std::vector<int> labels;
  labels.reserve(dataset.classes.size());
  for (const std::string& name : dataset.classes) {
    const auto found = index.find(name);
    if (found == index.end())
      throw Error("dataset", "class '" + name + "' is not in the class list");
    labels.push_back(found->second);
  }
  return labels;
}

std::vector<std::string> ordered_classes(const Dataset& dataset, const std::string& skin) {
  const std::vector<std::string> present = dataset.class_names();
  std::vector<std::string> ordered;
  for (const std::string& name : load_layout(skin).classes)
    if (std::find(present.begin(), present.end(), name) != present.end()) ordered.push_back(name);
  for (const std::string& name : present)
    if (std::find(ordered.begin(), ordered.end(), name) == ordered.end()) ordered.push_back(name);
  return ordered;
}

namespace {

// The rows `indices` (ascending) of x, copied a run of consecutive rows at a time: with
// thousands of columns (Robovie's pair correlations) row-by-row copies of a column-major
// matrix dominate a leave-one-out run.
Eigen::MatrixXd rows_of(const Eigen::MatrixXd& x, const std::vector<int64_t>& indices) {
  Eigen::MatrixXd rows(static_cast<Eigen::Index>(indices.size()), x.cols());
  size_t start = 0;
  while (start < indices.size()) {
    size_t end = start + 1;
    while (end < indices.size() && indices[end] == indices[end - 1] + 1) ++end;
    const auto length = static_cast<Eigen::Index>(end - start);
    rows.middleRows(static_cast<Eigen::Index>(start), length) =
        x.middleRows(indices[start], length);
    start = end;
  }
  return rows;
}

}  // namespace

Eigen::MatrixXi cross_validate(const Eigen::MatrixXd& x, const std::vector<int>& labels,
                               int class_count, const std::vector<ml::Fold>& folds,
                               const std::string& specification, uint64_t seed,
                               const ml::PcaOptions* pca,
                               const std::function<void(int done, int total)>& progress) {
  Eigen::MatrixXi confusion = Eigen::MatrixXi::Zero(class_count, class_count + 1);
  for (size_t fold = 0; fold < folds.size(); ++fold) {
    const std::vector<int64_t>& train = folds[fold].train;
    const std::vector<int64_t>& test = folds[fold].test;
    Eigen::MatrixXd train_x = rows_of(x, train);
    Eigen::MatrixXd test_x = rows_of(x, test);
    std::vector<int> train_y;
    for (const int64_t row : train) train_y.push_back(labels[static_cast<size_t>(row)]);
    if (pca) {
      const ml::Pca projection = ml::fit_pca(train_x, *pca);
      train_x = projection.transform(train_x);
      test_x = projection.transform(test_x);
    }
    auto classifier = ml::make_classifier(specification);
    classifier->fit(train_x, train_y, class_count, seed + fold);
    const std::vector<int> predicted = classifier->predict(test_x);
    for (size_t row = 0; row < test.size(); ++row) {
      const int truth = labels[static_cast<size_t>(test[row])];
      const int answer = predicted[row] == ml::kUnknownClass ? class_count : predicted[row];
      ++confusion(truth, answer);
    }
    if (progress) progress(static_cast<int>(fold + 1), static_cast<int>(folds.size()));
  }
  return confusion;
}

std::string percent_text(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", 100.0 * fraction);
  return text;
}

}  // namespace tactile::experiments
