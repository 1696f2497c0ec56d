#pragma once
// Saved models and predictions as labels: a classifier fitted on a feature table, saved
// with what produced its features (the skin, the feature pipeline and its columns, the
// classes), applied to the segments of new recordings. Its answers become labels of
// source `model` (the prediction lane), each with its score and margin.

#include <functional>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <span>
#include <string>
#include <vector>

#include "tactile/features/corpus.h"
#include "tactile/features/dataset.h"
#include "tactile/io/recording.h"
#include "tactile/labelstore/label.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/ml/classifier.h"

namespace tactile {

struct SavedModel {
  std::unique_ptr<ml::Classifier> classifier;
  std::vector<std::string> classes;   // index = the classifier's class index
  std::vector<std::string> features;  // the column names it was fitted on, in order
  std::string pipeline;               // feature pipeline name; "" when not known
  std::string pipeline_params;        // all its settings, "key=value,..."
  std::string layout;                 // the skin; "" when the table mixed or had none
  // Metadata every training recording shared (a device's calibration): what a stream without
  // metadata of its own (live packets) is given.
  Metadata recording_metadata;
};

// Fits `specification` on every row of `dataset`: the classifier with the classes, the
// features, the layout (the rows' `layout` metadata when all agree), the pipeline (as given:
// a skin's own is default_pipeline, skins/skin.h) and pipeline_params: every setting that
// pipeline reads, the given ones and the defaults of this build (see
// effective_pipeline_parameters). Throws tactile::Error on a bad pipeline or parameter.
SavedModel fit_model(const Dataset& dataset, const std::string& specification, uint64_t seed,
                     const std::string& pipeline = "", const std::string& pipeline_params = "");
// The model as its document (save_classifier's fields plus the rest), which
// model_from_json reads back to the same predictions.
nlohmann::json model_document(const SavedModel& model);
// model_document(fit_model(...)).
nlohmann::json fit_model_document(const Dataset& dataset, const std::string& specification,
                                  uint64_t seed, const std::string& pipeline = "",
                                  const std::string& pipeline_params = "");
// Written to a temporary file and renamed: a failed write leaves no half file.
void write_json_file(const std::string& path, const nlohmann::json& document,
                     const std::string& what);
// Reads a model document; `step(share of the file read)` is called while parsing (a job's
// progress and cancel). Throws tactile::Error naming the file and what is wrong.
SavedModel read_model_file(const std::string& path, const std::function<void(double)>& step = {});
SavedModel model_from_json(const nlohmann::json& document, const std::string& where);

// The annotator of every prediction label.
inline constexpr const char* kModelAnnotator = "model";

struct Predictions {
  std::vector<Label> labels;            // source kModel, one per predicted segment
  std::vector<SkippedSegment> skipped;  // segments the pipeline gave no row for
};
// Predicts the segments of one recording with the model's pipeline. Each label keeps the
// segment's bounds and region, class = the answer ("unknown" when the model answers so),
// confidence = its score and note "margin=M model=SPEC" (ml::confidence_of). Throws
// tactile::Error when the model has no pipeline, the recording is of another skin, or
// the pipeline's columns are not the model's features. `step(fraction of the segments)` is
// called after the pipeline's preprocessing and after each segment (a job's progress and
// cancel: the callback throws).
Predictions predict_segments(const SavedModel& model, const Recording& recording,
                             const SkinLayout& layout, const std::vector<Label>& segments,
                             const std::function<void(double)>& step = {});
// The same from a source's stream: a pipeline that reads only each segment's samples
// (FeatureExtractor::reads_segment_only) reads their windows alone, so a long recording is
// never held whole; any other reads the stream once. The same predictions either way.
Predictions predict_segments(const SavedModel& model, const SampleSource& source,
                             const SkinLayout& layout, const std::vector<Label>& segments,
                             const std::function<void(double)>& step = {});

// The segments a model predicts on by default: the recording's segmenter suggestions among
// `labels` (one recording's), else its ground truth; none when it has neither.
std::vector<Label> segments_to_predict(const std::vector<Label>& labels);

// The model's lane of a recording replaced by `predictions`, as one edit: its earlier
// predictions removed, the new ones added (LabelStore::apply, by kModelAnnotator or the
// person who asked). Returns the edit and, in `replaced`, how many it removes.
LabelEdit prediction_edit(const LabelStore& store, const std::string& recording,
                          const std::vector<Label>& predictions, size_t* replaced = nullptr);

// The margin a prediction label carries in its note ("margin=0.25 ..."); its confidence
// when the note has none.
double prediction_margin(const Label& label);

// The prediction an operator should look at next: the one with the smallest margin that no
// label of `decided` (the operator's own lane) overlaps yet. Null when every one is decided.
const Label* least_sure_prediction(std::span<const Label> predictions,
                                   std::span<const Label> decided);

}  // namespace tactile
