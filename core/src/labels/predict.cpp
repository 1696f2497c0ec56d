// Saved models (fit on a table, save with their pipeline) and their predictions as labels.
#include "tactile/labels/predict.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tactile/error.h"
#include "tactile/features/feature_extractor.h"
#include "tactile/io/atomic_file.h"
#include "tactile/ml/grid_search.h"
#include "tactile/parameters.h"
#include "tactile/text.h"

namespace tactile {

SavedModel fit_model(const Dataset& dataset, const std::string& specification, uint64_t seed,
                     const std::string& pipeline, const std::string& pipeline_params) {
  SavedModel model;
  model.classes = dataset.class_names();
  std::map<std::string, int> index;
  for (size_t k = 0; k < model.classes.size(); ++k) index[model.classes[k]] = static_cast<int>(k);
  std::vector<int> labels;
  labels.reserve(dataset.classes.size());
  for (const std::string& name : dataset.classes) labels.push_back(index.at(name));
  // auto on a stacked table searches its pipelines too.
  model.classifier =
      ml::make_classifier(ml::searched_specification(specification, dataset.columns));
  model.classifier->fit(dataset.features, labels, static_cast<int>(model.classes.size()), seed);
  for (const FeatureColumn& column : dataset.columns) model.features.push_back(column.name);
  // The skin, when every row names the same one.
  model.layout = dataset.shared_metadata("layout");
  model.pipeline = pipeline;
  // Every setting of the pipeline, defaults included, so that predicting with this model
  // extracts as its training data was extracted even after a default changes.
  model.pipeline_params = pipeline.empty() ? pipeline_params
                                           : effective_pipeline_parameters(
                                                 pipeline, pipeline_params, "pipeline parameters");
  // What every recording it learnt from had in common (a device's calibration, its signal
  // convention): given to a stream that carries no metadata (live packets).
  if (!dataset.metadata.empty()) {
    for (const auto& entry : dataset.metadata.front()) {
      const std::string& key = entry.first;
      const std::string& value = entry.second;
      // Not the row's own place, and not what the pipeline did to it (a
      // stream given "preprocessed" would claim to be preprocessed already).
      if (key == "t0" || key == "t1" || key == "region" || key == "subject" || key == "trial" ||
          key == "recording" || key == "segment_id" || key == "layout" || key == "preprocessing" ||
          key == "preprocessed" || key.find('.') != std::string::npos)  // a pipeline's own notes
        continue;
      const bool shared =
          std::all_of(dataset.metadata.begin(), dataset.metadata.end(), [&](const Metadata& row) {
            const auto found = row.find(key);
            return found != row.end() && found->second == value;
          });
      if (shared) model.recording_metadata[key] = value;
    }
  }
  return model;
}

nlohmann::json model_document(const SavedModel& model) {
  nlohmann::json document = ml::save_classifier(*model.classifier);
  document["classes"] = model.classes;
  document["features"] = model.features;
  document["layout"] = model.layout;
  document["pipeline"] = model.pipeline;
  document["pipeline_params"] = model.pipeline_params;
  nlohmann::json common = nlohmann::json::object();
  for (const auto& [key, value] : model.recording_metadata) common[key] = value;
  document["recording_metadata"] = common;
  return document;
}

nlohmann::json fit_model_document(const Dataset& dataset, const std::string& specification,
                                  uint64_t seed, const std::string& pipeline,
                                  const std::string& pipeline_params) {
  return model_document(fit_model(dataset, specification, seed, pipeline, pipeline_params));
}

void write_json_file(const std::string& path, const nlohmann::json& document,
                     const std::string& what) {
  // Streamed to the file: a kernel SVM's or a linear one's 105 directions of Robovie's 37,401
  // features are 112 MB of text, which a dump() held in memory at once.
  write_file_atomically(
      path,
      [&](const std::string& temporary) {
        std::ofstream out(temporary, std::ios::binary);
        out << std::setw(1) << document << "\n";
        out.flush();
        if (!out) throw Error(path, "cannot write the " + what);
      },
      what);
}

SavedModel model_from_json(const nlohmann::json& document, const std::string& where) {
  SavedModel model;
  try {
    model.classifier = ml::load_classifier(document);
  } catch (const Error& error) {
    throw Error(where, error.what());
  }
  const auto strings = [&](const char* key) {
    if (!document.contains(key) || !document[key].is_array())
      throw Error(where, std::string("missing '") + key + "' (a list of names)");
    std::vector<std::string> names;
    for (const nlohmann::json& item : document[key]) {
      if (!item.is_string()) throw Error(where, std::string("'") + key + "' holds a non-string");
      names.push_back(item.get<std::string>());
    }
    return names;
  };
  const auto text = [&](const char* key) {
    if (!document.contains(key)) return std::string();
    if (!document[key].is_string()) throw Error(where, std::string("'") + key + "' is not text");
    return document[key].get<std::string>();
  };
  model.classes = strings("classes");
  model.features = strings("features");
  if (model.classes.empty()) throw Error(where, "'classes' is empty");
  model.pipeline = text("pipeline");
  model.pipeline_params = text("pipeline_params");
  model.layout = text("layout");
  if (document.contains("recording_metadata")) {
    const nlohmann::json& common = document["recording_metadata"];
    if (!common.is_object()) throw Error(where, "'recording_metadata' is not an object");
    for (const auto& [key, value] : common.items()) {
      if (!value.is_string()) throw Error(where, "'recording_metadata' " + key + " is not text");
      model.recording_metadata[key] = value.get<std::string>();
    }
  }
  return model;
}

SavedModel read_model_file(const std::string& path, const std::function<void(double)>& step) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open the model");
  nlohmann::json document;
  // A model can be large (a kernel SVM keeps its support vectors): the parse calls `step`
  // every 64k values with the share of the file read.
  std::error_code error;
  const double size = static_cast<double>(std::filesystem::file_size(path, error));
  int64_t values = 0;
  nlohmann::json::parser_callback_t each = nullptr;
  if (step)
    each = [&](int, nlohmann::json::parse_event_t, nlohmann::json&) {
      if (++values % 65536 == 0 && size > 0)
        step(std::min(1.0, static_cast<double>(in.tellg()) / size));
      return true;
    };
  try {
    document = nlohmann::json::parse(in, each);
  } catch (const nlohmann::json::exception& failure) {
    throw Error(path, std::string("not JSON: ") + failure.what());
  }
  if (step) step(1.0);
  return model_from_json(document, path);
}

namespace {

// The model's pipeline, checked against the layout and the model's features.
std::unique_ptr<FeatureExtractor> model_extractor(const SavedModel& model, const SkinLayout& layout,
                                                  const std::string& where,
                                                  std::vector<FeatureColumn>& columns) {
  if (model.pipeline.empty())
    throw Error(where, "the model does not say which feature pipeline made its features");
  if (!model.layout.empty() && model.layout != layout.id)
    throw Error(where,
                "a recording of skin '" + layout.id + "', the model is for '" + model.layout + "'");
  auto extractor = make_feature_extractor(
      model.pipeline, Parameters::parse(model.pipeline_params, "model pipeline_params"));
  columns = extractor->columns(layout);
  bool same = columns.size() == model.features.size();
  for (size_t i = 0; same && i < columns.size(); ++i) same = columns[i].name == model.features[i];
  if (!same)
    throw Error(where, "pipeline " + model.pipeline + " gives " + std::to_string(columns.size()) +
                           " columns on " + layout.id + ", not the model's " +
                           std::to_string(model.features.size()) + " features");
  return extractor;
}

// Rows asked of a model at once, and segments whose windows are read at once: 16 rows of
// Robovie's 37,401 correlations are 4.8 MB (64 were 19 MB, held three times over as values,
// the batch's rows and their standardized copy).
constexpr size_t kPredictBatch = 16;

// The model's answer for every segment the pipeline gave a row for, asked a batch of rows at
// a time (each row's answer is its own) and each segment's values dropped once asked: 195
// segments of Robovie's 37,401 correlations were 58 MB, copied twice more before.
Predictions classify_segments(const SavedModel& model, const std::string& recording,
                              const std::vector<FeatureColumn>& columns,
                              const std::vector<Label>& segments,
                              FeatureExtractor::Segments extracted) {
  Predictions predictions;
  std::vector<size_t> kept;
  for (size_t index = 0; index < segments.size(); ++index) {
    const Label& segment = segments[index];
    const FeatureResult& result = extracted.results[index];
    std::string reason = result.skip_reason;
    if (reason.empty() && result.values.size() != columns.size())
      reason = "extractor gave " + std::to_string(result.values.size()) + " values";
    for (size_t i = 0; reason.empty() && i < result.values.size(); ++i)
      if (!std::isfinite(result.values[i])) reason = "non-finite value in " + columns[i].name;
    if (!reason.empty()) {
      predictions.skipped.push_back({recording, segment.id, segment.t0, segment.t1, reason});
      continue;
    }
    kept.push_back(index);
  }
  const std::string specification = ml::specification_of(*model.classifier);
  for (size_t from = 0; from < kept.size(); from += kPredictBatch) {
    const size_t count = std::min(kPredictBatch, kept.size() - from);
    ml::Matrix x(static_cast<Eigen::Index>(count), static_cast<Eigen::Index>(columns.size()));
    for (size_t row = 0; row < count; ++row) {
      std::vector<double>& values = extracted.results[kept[from + row]].values;
      x.row(static_cast<Eigen::Index>(row)) = Eigen::Map<const Eigen::RowVectorXd>(
          values.data(), static_cast<Eigen::Index>(values.size()));
      std::vector<double>().swap(values);
    }
    const ml::Classifier::Decisions decisions = model.classifier->decide(x);
    for (size_t row = 0; row < count; ++row) {
      const Label& segment = segments[kept[from + row]];
      const int answer = decisions.classes[row];
      const ml::Confidence confidence = ml::confidence_of(
          decisions.scores.row(static_cast<Eigen::Index>(row)).transpose(), answer);
      Label label;
      label.recording = recording;
      label.t0 = segment.t0;
      label.t1 = segment.t1;
      label.region = segment.region;
      label.class_name = answer >= 0 && answer < static_cast<int>(model.classes.size())
                             ? model.classes[static_cast<size_t>(answer)]
                             : std::string(kUnknownClass);
      label.annotator = kModelAnnotator;
      label.source = LabelSource::kModel;
      label.confidence = std::clamp(confidence.score, 0.0, 1.0);
      label.note = "margin=" + significant_text(confidence.margin, 4) + " model=" + specification;
      predictions.labels.push_back(std::move(label));
    }
  }
  return predictions;
}

}  // namespace

Predictions predict_segments(const SavedModel& model, const Recording& recording,
                             const SkinLayout& layout, const std::vector<Label>& segments,
                             const std::function<void(double)>& step) {
  const std::string where = recording.id.empty() ? std::string("predict") : recording.id;
  std::vector<FeatureColumn> columns;
  const auto extractor = model_extractor(model, layout, where, columns);
  if (step) step(0.0);
  FeatureExtractor::Segments extracted =
      extractor->extract_segments(recording, layout, segments, [&](size_t done) {
        if (step) step(static_cast<double>(done) / static_cast<double>(segments.size()));
      });
  return classify_segments(model, recording.id, columns, segments, std::move(extracted));
}

Predictions predict_segments(const SavedModel& model, const SampleSource& source,
                             const SkinLayout& layout, const std::vector<Label>& segments,
                             const std::function<void(double)>& step) {
  const std::string& id = source.info().recording_id;
  std::vector<FeatureColumn> columns;
  const auto extractor = model_extractor(model, layout, id.empty() ? "predict" : id, columns);
  const auto segment_done = [&](size_t done, double read_share) {
    if (step)
      step(read_share +
           (1.0 - read_share) * static_cast<double>(done) / static_cast<double>(segments.size()));
  };
  if (step) step(0.0);
  if (!extractor->reads_segment_only()) {
    // Reading the whole stream (a pipeline that preprocesses it) is the first third.
    constexpr double kReadShare = 1.0 / 3.0;
    FeatureExtractor::Segments extracted = extract_source_segments(
        *extractor, source, layout, segments, [&](size_t done) { segment_done(done, kReadShare); },
        [&](double share) {
          if (step) step(kReadShare * share);
        });
    return classify_segments(model, id, columns, segments, std::move(extracted));
  }
  // Each segment's window alone, a batch at a time: the features of a batch, not of every
  // segment, are held at once.
  Predictions predictions;
  for (size_t from = 0; from < segments.size(); from += kPredictBatch) {
    const std::vector<Label> batch(segments.begin() + static_cast<std::ptrdiff_t>(from),
                                   segments.begin() + static_cast<std::ptrdiff_t>(std::min(
                                                          segments.size(), from + kPredictBatch)));
    Predictions part = classify_segments(
        model, id, columns, batch,
        extract_source_segments(*extractor, source, layout, batch,
                                [&](size_t done) { segment_done(from + done, 0.0); }));
    std::move(part.labels.begin(), part.labels.end(), std::back_inserter(predictions.labels));
    std::move(part.skipped.begin(), part.skipped.end(), std::back_inserter(predictions.skipped));
  }
  return predictions;
}

std::vector<Label> segments_to_predict(const std::vector<Label>& labels) {
  std::vector<Label> segments;
  for (const LabelSource source : {LabelSource::kSegmenter, LabelSource::kGroundTruth}) {
    for (const Label& label : labels)
      if (label.source == source) segments.push_back(label);
    if (!segments.empty()) break;
  }
  return segments;
}

LabelEdit prediction_edit(const LabelStore& store, const std::string& recording,
                          const std::vector<Label>& predictions, size_t* replaced) {
  LabelFilter earlier;
  earlier.recording = recording;
  earlier.source = LabelSource::kModel;
  LabelEdit edit;
  for (const Label& label : store.list(earlier)) edit.remove.push_back(ref_of(label));
  if (replaced != nullptr) *replaced = edit.remove.size();
  edit.add = predictions;
  return edit;
}

double prediction_margin(const Label& label) {
  const size_t at = label.note.find("margin=");
  if (at == std::string::npos) return label.confidence;
  const char* start = label.note.c_str() + at + 7;
  char* end = nullptr;
  const double margin = std::strtod(start, &end);
  return end != start && std::isfinite(margin) ? margin : label.confidence;
}

const Label* least_sure_prediction(std::span<const Label> predictions,
                                   std::span<const Label> decided) {
  const Label* best = nullptr;
  double best_margin = 0.0;
  for (const Label& label : predictions) {
    const bool covered = std::any_of(decided.begin(), decided.end(), [&](const Label& mine) {
      return mine.t0 < label.t1 && label.t0 < mine.t1;
    });
    if (covered) continue;
    const double margin = prediction_margin(label);
    if (!best || margin < best_margin) best = &label, best_margin = margin;
  }
  return best;
}

}  // namespace tactile
