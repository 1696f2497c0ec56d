#include "kaboli_common.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "tactile/error.h"
#include "tactile/features/feature_extractor.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/ml/classifier.h"
#include "tactile/ml/evaluation.h"
#include "tactile/segment/segmenter.h"
#include "tactile/skins/workspace.h"

namespace tactile::experiments::kaboli {

const std::vector<std::string> kClasses = {"pat",     "poke", "punch",  "push",  "rub",
                                           "scratch", "slap", "stroke", "tickle"};

namespace {

struct SetDesign {
  const char* name;
  const char* query;  // rows of the set in a data folder (recording metadata)
  const char* side;
  const char* condition;
  bool multi_touch;
  int repetitions;    // touches per class and subject (spec §1.17: 3 train, 4 test)
  const char* group;  // who performs it: the same people for both training sets
};

SetDesign design_of(Set set) {
  switch (set) {
    case Set::kBackStationary:
      return {"back-stationary",
              "side=back,condition=stationary",
              "back",
              "stationary",
              false,
              3,
              "train"};
    case Set::kFrontStationary:
      return {"front-stationary",
              "side=front,condition=stationary",
              "front",
              "stationary",
              false,
              4,
              "test"};
    case Set::kBackMoving:
      return {"back-moving", "side=back,condition=moving", "back", "moving", false, 3, "train"};
    case Set::kFrontMoving:
      return {"front-moving", "side=front,condition=moving", "front", "moving", false, 4, "test"};
    case Set::kMultiTouch:
      return {"multi-touch", "scenario=multi-touch", "", "moving", true, 4, "multi"};
  }
  throw Error("experiment", "unknown Kaboli set");
}

// Each group of people gets its own seed so that test subjects never share the habits of
// training subjects (spec §1.17: subjects never overlap).
uint64_t group_seed(uint64_t seed, const std::string& group) {
  if (group == "train") return seed;
  return derive_engine(seed, "kaboli-subjects-" + group)();
}

// The ground-truth touch on the segment's body part that overlaps it longest (first of
// equals); kUnknownClass when none does. Regions matter: in multi-touch trials a front and a
// back touch overlap in time.
std::string class_on_region(const Label& segment, const std::vector<Label>& truth) {
  std::string best = kUnknownClass;
  double best_overlap = 0.0;
  for (const Label& label : truth) {
    if (label.region != segment.region) continue;
    const double overlap = std::min(label.t1, segment.t1) - std::max(label.t0, segment.t0);
    if (overlap > best_overlap) {
      best_overlap = overlap;
      best = label.class_name;
    }
  }
  return best;
}

Dataset subset(const Dataset& dataset, const std::vector<int64_t>& rows) {
  Dataset out;
  out.columns = dataset.columns;
  out.features.resize(static_cast<Eigen::Index>(rows.size()), dataset.features.cols());
  for (size_t i = 0; i < rows.size(); ++i) {
    const auto row = static_cast<size_t>(rows[i]);
    out.features.row(static_cast<Eigen::Index>(i)) = dataset.features.row(rows[i]);
    out.classes.push_back(dataset.classes[row]);
    out.subjects.push_back(dataset.subjects[row]);
    out.recordings.push_back(dataset.recordings[row]);
    out.segment_ids.push_back(dataset.segment_ids[row]);
    out.metadata.push_back(dataset.metadata[row]);
  }
  return out;
}

}  // namespace

std::string set_name(Set set) { return design_of(set).name; }

std::string percent(double fraction) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f", 100.0 * fraction);
  return text;
}

Corpus::Corpus(const ExperimentOptions& options) : options_(options) {
  if (options_.data_dir.empty() && options_.work_dir.empty())
    throw Error("experiment", "needs a data folder or a work folder to simulate into");
}

void Corpus::report(const std::string& stage, int done, int total) const {
  if (options_.progress) options_.progress(stage, done, total);
}

Corpus::Source& Corpus::source(Set set) {
  const SetDesign design = design_of(set);
  const std::string folder = options_.data_dir.empty()
                                 ? (std::filesystem::path(options_.work_dir) / design.name).string()
                                 : options_.data_dir;
  auto found = sources_.find(folder);
  if (found != sources_.end()) return found->second;

  if (options_.data_dir.empty()) {
    SimulationOptions simulation;
    simulation.subjects = options_.quick ? 2 : 6;
    simulation.trials = 1;
    simulation.seed = group_seed(options_.seed, design.group);
    simulation.condition = design.condition;
    simulation.multi_touch = design.multi_touch;
    simulation.side = design.side;
    simulation.repetitions = options_.quick ? 2 : design.repetitions;
    const std::string stage = std::string("simulate ") + design.name;
    // The set's folder belongs to the experiment: clear what an earlier run (perhaps with more
    // subjects) left there, so its recordings never mix into this one.
    std::filesystem::remove_all(folder);
    write_simulation(folder, "nao", simulation,
                     [&](int done, int total) { report(stage, done, total); });
  }

  const std::string database = (std::filesystem::path(folder) / "labels.db").string();
  if (!std::filesystem::is_regular_file(database))
    throw Error(database, "no label database (the experiment needs ground-truth labels)");
  LabelStore store(database, LabelStore::OpenMode::kExisting);
  LabelFilter filter;
  filter.source = LabelSource::kGroundTruth;
  std::map<std::string, std::vector<Label>> truth;
  for (Label& label : store.list(filter)) truth[label.recording].push_back(std::move(label));
  if (truth.empty()) throw Error(database, "no ground-truth labels");

  Source source;
  source.folder = folder;
  int done = 0;
  for (auto& [id, labels] : truth) {
    CorpusRecording recording;
    recording.id = id;
    recording.path = (std::filesystem::path(folder) / (id + ".h5")).string();
    if (!std::filesystem::is_regular_file(recording.path))
      throw Error(recording.path, "recording file missing (it has labels in " + database + ")");
    const Recording data = read_recording(recording.path);
    const SkinLayout layout = load_layout(data.layout_id);
    // Segment as a person would see the stream (spec §1.1: proximity window), then name each
    // segment by the ground truth only to score it.
    recording.segments = segment_recording("proximity", data, layout);
    for (Label& segment : recording.segments) segment.class_name = class_on_region(segment, labels);
    recording.ground_truth = labels;
    source.recordings.push_back(std::move(recording));
    report(std::string("segment ") + design.name, ++done, static_cast<int>(truth.size()));
  }
  return sources_.emplace(folder, std::move(source)).first->second;
}

Dataset Corpus::dataset(Set set, const std::string& pipeline) {
  const SetDesign design = design_of(set);
  Source& data = source(set);
  const std::string key = data.folder + "\n" + pipeline;
  auto found = datasets_.find(key);
  if (found == datasets_.end()) {
    const auto extractor = make_feature_extractor(pipeline);
    CorpusOptions corpus_options;
    const std::string stage = "features " + pipeline;
    corpus_options.progress = [&](int64_t done, int64_t total) {
      report(stage, static_cast<int>(done), static_cast<int>(total));
    };
    CorpusDataset corpus = extract_corpus(*extractor, data.recordings, corpus_options);
    if (corpus.dataset.rows() == 0)
      throw Error(data.folder, "no feature rows (" + std::to_string(corpus.skipped.size()) +
                                   " segments skipped)");
    found = datasets_.emplace(key, std::move(corpus.dataset)).first;
  }
  const Dataset& all = found->second;
  const std::vector<int64_t> rows = ml::rows_matching(all, design.query, data.folder);
  std::vector<int64_t> touches;
  for (int64_t row : rows)
    if (std::find(kClasses.begin(), kClasses.end(), all.classes[static_cast<size_t>(row)]) !=
        kClasses.end())
      touches.push_back(row);
  if (touches.empty())
    throw Error(data.folder,
                std::string("no segment of set ") + design.name + " overlaps a ground-truth touch");
  set_notes_[design.name] = std::string(design.name) + ": " + std::to_string(touches.size()) +
                            " segments from " + data.folder + " (" +
                            std::to_string(rows.size() - touches.size()) +
                            " segments without a ground-truth touch left out)";
  return subset(all, touches);
}

std::string Corpus::notes() const {
  std::string text;
  for (const auto& [name, note] : set_notes_) text += (text.empty() ? "" : "; ") + note;
  if (options_.data_dir.empty())
    text += std::string("; simulated NAO skin (") +
            (options_.quick ? "quick: 2 subjects" : "6 subjects") + " per set, seed " +
            std::to_string(options_.seed) + ")";
  return text;
}

Scored train_and_test(const Dataset& train, const Dataset& test, const std::string& classifier,
                      uint64_t seed) {
  auto index_of = [](const std::string& name) {
    return static_cast<int>(std::find(kClasses.begin(), kClasses.end(), name) - kClasses.begin());
  };
  std::vector<int> train_classes;
  for (const std::string& name : train.classes) train_classes.push_back(index_of(name));
  auto model = ml::make_classifier(classifier);
  model->fit(train.features, train_classes, kClassCount, seed);
  const std::vector<int> predicted = model->predict(test.features);
  Scored scored;
  scored.train_rows = train.rows();
  scored.confusion = Eigen::MatrixXi::Zero(kClassCount, kClassCount + 1);
  for (size_t row = 0; row < predicted.size(); ++row) {
    const int column = predicted[row] == ml::kUnknownClass ? kClassCount : predicted[row];
    scored.confusion(index_of(test.classes[row]), column) += 1;
  }
  scored.accuracy = ml::accuracy_of(scored.confusion);
  scored.model = std::move(model);
  return scored;
}

std::string svm_specification(bool quick) {
  const int values = quick ? 5 : 20;
  std::string grid;
  for (int k = 0; k < values; ++k) {
    // Spec §1.14: C_k = 10^(-3 + 6k/19), 1e-3 ... 1e3.
    char text[32];
    std::snprintf(text, sizeof(text), "%.6g",
                  std::pow(10.0, -3.0 + 6.0 * k / static_cast<double>(values - 1)));
    if (k > 0) grid += '|';
    grid += text;
  }
  return "grid:base=linear-svm,c=" + grid + ",inner=" + (quick ? "kfold:3" : "kfold:5x10");
}

double paper_accuracy_of(const PaperMatrix& matrix) {
  int correct = 0, all = 0;
  for (int row = 0; row < kClassCount; ++row)
    for (int column = 0; column < kClassCount; ++column) {
      all += matrix[row][column];
      if (row == column) correct += matrix[row][column];
    }
  return all == 0 ? 0.0 : static_cast<double>(correct) / all;
}

ReportTable confusion_table(const std::string& title, const Scored& ours, const PaperMatrix& paper,
                            double paper_accuracy, const std::string& note) {
  ReportTable table;
  table.title = title;
  table.columns = {"true \\ predicted"};
  for (const std::string& name : kClasses) table.columns.push_back(name);
  table.columns.insert(table.columns.end(), {"unknown", "ours %", "paper %"});
  for (int row = 0; row < kClassCount; ++row) {
    std::vector<std::string> cells = {kClasses[static_cast<size_t>(row)]};
    int total = 0, paper_total = 0;
    for (int column = 0; column <= kClassCount; ++column) {
      cells.push_back(std::to_string(ours.confusion(row, column)));
      total += ours.confusion(row, column);
    }
    for (int column = 0; column < kClassCount; ++column) paper_total += paper[row][column];
    cells.push_back(total == 0 ? "-" : percent(ours.confusion(row, row) / double(total)));
    cells.push_back(paper_total == 0 ? "-" : percent(paper[row][row] / double(paper_total)));
    table.rows.push_back(std::move(cells));
  }
  std::vector<std::string> total(table.columns.size(), "");
  total[0] = "accuracy";
  total[total.size() - 2] = percent(ours.accuracy);
  total[total.size() - 1] = percent(paper_accuracy);
  table.rows.push_back(std::move(total));
  table.note = note;
  return table;
}

nlohmann::json confusion_json(const std::string& title, const Scored& ours,
                              const PaperMatrix& paper, double paper_accuracy) {
  nlohmann::json json;
  json["title"] = title;
  json["classes"] = kClasses;
  json["accuracy"] = ours.accuracy;
  json["paper_accuracy"] = paper_accuracy;
  json["paper_matrix_accuracy"] = paper_accuracy_of(paper);
  json["train_rows"] = ours.train_rows;
  nlohmann::json confusion = nlohmann::json::array(), paper_confusion = nlohmann::json::array();
  for (int row = 0; row < kClassCount; ++row) {
    std::vector<int> cells;
    for (int column = 0; column <= kClassCount; ++column)
      cells.push_back(ours.confusion(row, column));
    confusion.push_back(cells);
    paper_confusion.push_back(paper[static_cast<size_t>(row)]);
  }
  json["confusion"] = confusion;
  json["paper_confusion"] = paper_confusion;
  return json;
}

}  // namespace tactile::experiments::kaboli
