// Label Studio's JSON export of time-series labels both ways (elan_and_label_studio.h): a list of
// tasks, each with annotations (people; "ground_truth": true for ground truth) and predictions
// (segmenters and models), each holding "timeserieslabels" results with start and end.
#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

#include "tactile/error.h"
#include "tactile/labels/elan_and_label_studio.h"
#include "tactile/labels/label_format.h"
#include "tactile/labels/lanes.h"
#include "tactile/text.h"

namespace tactile {

namespace {

// Our keys for what Label Studio has no field for (the annotator's name, the skin region): read
// back so that our own exports return every field. Whether Label Studio keeps them through its
// own import and export is not checked here; without them a label comes back under
// "label-studio:USER" (or --annotator's name) and region "all".
constexpr const char* kStudioAnnotatorKey = "tactile_annotator";
constexpr const char* kStudioRegionKey = "tactile_region";

nlohmann::json studio_result(const Label& label, size_t index, bool prediction) {
  nlohmann::json result{{"id", "r" + std::to_string(index)},
                        {"from_name", "label"},
                        {"to_name", "ts"},
                        {"type", "timeserieslabels"},
                        {"origin", prediction ? "prediction" : "manual"},
                        {"value",
                         {{"start", label.t0},
                          {"end", label.t1},
                          {"instant", false},
                          {"timeserieslabels", {label.class_name}}}}};
  if (prediction || label.confidence != 1.0) result["score"] = label.confidence;
  if (label.region != "all") result[kStudioRegionKey] = label.region;
  // Label Studio shows a region's meta text beside it: our note.
  if (!label.note.empty()) result["meta"] = {{"text", {label.note}}};
  return result;
}

// A task's recording: data.recording, else the first file named in data without folder,
// extension and the 8-character prefix Label Studio gives uploads ("1a2b3c4d-").
std::string studio_recording_of(const nlohmann::json& data) {
  if (!data.is_object()) return {};
  if (data.contains("recording") && data["recording"].is_string())
    return data["recording"].get<std::string>();
  for (const auto& [key, value] : data.items()) {
    if (!value.is_string()) continue;
    std::string name = value.get<std::string>();
    const size_t query = name.find('?');
    if (query != std::string::npos) name = name.substr(0, query);
    const size_t slash = name.find_last_of('/');
    if (slash != std::string::npos) name = name.substr(slash + 1);
    const size_t dot = name.find_last_of('.');
    if (dot != std::string::npos && dot > 0) name = name.substr(0, dot);
    if (name.size() > 9 && name[8] == '-' &&
        std::all_of(name.begin(), name.begin() + 8,
                    [](char c) { return std::isxdigit(static_cast<unsigned char>(c)); }))
      name = name.substr(9);
    if (!name.empty()) return name;
  }
  return {};
}

// completed_by as Label Studio writes it: a user id, or an object with the id and email.
std::string studio_user_of(const nlohmann::json& annotation) {
  if (!annotation.contains("completed_by")) return {};
  const nlohmann::json& user = annotation["completed_by"];
  if (user.is_number_integer()) return std::to_string(user.get<int64_t>());
  if (user.is_string()) return user.get<std::string>();
  if (user.is_object()) {
    if (user.contains("email") && user["email"].is_string())
      return user["email"].get<std::string>();
    if (user.contains("id") && user["id"].is_number_integer())
      return std::to_string(user["id"].get<int64_t>());
  }
  return {};
}

double studio_number(const nlohmann::json& value, const char* key, const std::string& at) {
  if (!value.contains(key)) throw Error(at, std::string("no '") + key + "'");
  const nlohmann::json& number = value[key];
  if (!number.is_number())
    throw Error(at, std::string("'") + key +
                        "' is not a number (a time column of dates? give times in seconds)");
  const double seconds = number.get<double>();
  if (!std::isfinite(seconds)) throw Error(at, std::string("'") + key + "' is not finite");
  return seconds;
}

// The labels of one annotation's or prediction's results.
void studio_read_results(const nlohmann::json& results, const std::string& at_owner,
                         const std::string& recording, const LaneKey& lane,
                         const std::string& annotator, std::optional<double> owner_score,
                         std::vector<Label>& labels) {
  if (!results.is_array()) throw Error(at_owner, "'result' is not a list");
  for (size_t k = 0; k < results.size(); ++k) {
    const nlohmann::json& result = results[k];
    if (!result.is_object())
      throw Error(at_owner + " result " + std::to_string(k + 1), "not an object");
    const std::string id = result.contains("id") && result["id"].is_string()
                               ? result["id"].get<std::string>()
                               : std::to_string(k + 1);
    const std::string at = at_owner + " result '" + id + "'";
    // Other controls of the project (choices, text areas) are not labels.
    if (!result.contains("type") || result["type"] != "timeserieslabels") continue;
    if (!result.contains("value") || !result["value"].is_object()) throw Error(at, "no 'value'");
    const nlohmann::json& value = result["value"];
    if (value.contains("instant") && value["instant"].is_boolean() && value["instant"].get<bool>())
      throw Error(at, "an instant, not a span: a label needs a start and an end");
    Label label;
    label.recording = recording;
    label.t0 = studio_number(value, "start", at);
    label.t1 = studio_number(value, "end", at);
    if (!(label.t1 > label.t0))
      throw Error(at, "ends at " + shortest_text(label.t1) + " s, not after its start " +
                          shortest_text(label.t0) + " s");
    if (!value.contains("timeserieslabels") || !value["timeserieslabels"].is_array() ||
        value["timeserieslabels"].size() != 1 || !value["timeserieslabels"][0].is_string())
      throw Error(at, "'timeserieslabels' must hold exactly one label name");
    label.class_name = value["timeserieslabels"][0].get<std::string>();
    if (label.class_name.empty()) throw Error(at, "an empty label name");
    label.source = lane.source;
    label.annotator = annotator;
    if (result.contains("score") || owner_score) {
      const double score =
          result.contains("score") ? studio_number(result, "score", at) : *owner_score;
      if (!(score >= 0.0 && score <= 1.0))
        throw Error(at, "score " + shortest_text(score) + " is not in [0, 1]");
      label.confidence = score;
    }
    if (result.contains(kStudioRegionKey)) {
      if (!result[kStudioRegionKey].is_string() ||
          result[kStudioRegionKey].get<std::string>().empty())
        throw Error(at, std::string("'") + kStudioRegionKey + "' is not a region name");
      label.region = result[kStudioRegionKey].get<std::string>();
    }
    if (result.contains("meta") && result["meta"].is_object() && result["meta"].contains("text")) {
      const nlohmann::json& text = result["meta"]["text"];
      if (text.is_string()) label.note = text.get<std::string>();
      if (text.is_array())
        for (const nlohmann::json& line : text) {
          if (!line.is_string()) throw Error(at, "meta text is not text");
          label.note += (label.note.empty() ? "" : "\n") + line.get<std::string>();
        }
    }
    labels.push_back(std::move(label));
  }
}

// The export's list of tasks (one task alone is taken as a list of one).
nlohmann::json studio_tasks(const std::string& text, const std::string& where) {
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& error) {
    throw Error(where, std::string("not JSON: ") + error.what());
  }
  if (document.is_object()) document = nlohmann::json::array({document});
  if (!document.is_array())
    throw Error(where, "expected Label Studio's JSON export: a list of tasks");
  return document;
}

}  // namespace

std::string labels_label_studio(const std::vector<Label>& labels) {
  // Per recording, per lane and (for ground truth) per annotator: one annotation or prediction.
  std::map<std::string, std::vector<Label>> by_recording;
  for (const Label& label : labels) by_recording[label.recording].push_back(label);
  nlohmann::json tasks = nlohmann::json::array();
  size_t next_result = 1;
  int64_t next_annotation = 1;
  std::map<std::string, int64_t> user_ids;  // a stable number per annotator
  for (const auto& [recording, members] : by_recording) {
    nlohmann::json annotations = nlohmann::json::array(), predictions = nlohmann::json::array();
    const Lanes lanes = group_into_lanes(members);
    for (size_t k = 0; k < lanes.keys.size(); ++k) {
      const LaneKey& key = lanes.keys[k];
      const bool prediction =
          key.source == LabelSource::kSegmenter || key.source == LabelSource::kModel;
      // Ground truth keeps each label's annotator: one annotation per annotator.
      std::map<std::string, nlohmann::json> results;
      for (const Label& label : lanes.lanes[k].labels())
        results[label.annotator].push_back(studio_result(label, next_result++, prediction));
      for (auto& [annotator, list] : results) {
        if (prediction) {
          predictions.push_back({{"model_version", key.id()}, {"result", std::move(list)}});
          continue;
        }
        if (!user_ids.count(annotator))
          user_ids[annotator] = static_cast<int64_t>(user_ids.size()) + 1;
        annotations.push_back({{"id", next_annotation++},
                               {"completed_by", user_ids[annotator]},
                               {kStudioAnnotatorKey, annotator},
                               {"ground_truth", key.source == LabelSource::kGroundTruth},
                               {"was_cancelled", false},
                               {"result", std::move(list)}});
      }
    }
    tasks.push_back({{"id", static_cast<int64_t>(tasks.size()) + 1},
                     {"data", {{"csv", recording + ".csv"}, {"recording", recording}}},
                     {"annotations", std::move(annotations)},
                     {"predictions", std::move(predictions)}});
  }
  return tasks.dump(2) + "\n";
}

InteropSources label_studio_sources(const std::string& text, const std::string& where) {
  const nlohmann::json document = studio_tasks(text, where);
  InteropSources found;
  found.format = "Label Studio";
  std::vector<std::string> recordings;
  // The same names and default lanes parse_label_studio gives, counted per source.
  auto count = [&found](const std::string& name, const std::string& lane,
                        const nlohmann::json& owner) {
    auto source =
        std::find_if(found.sources.begin(), found.sources.end(),
                     [&](const InteropSource& s) { return s.name == name && s.lane == lane; });
    if (source == found.sources.end()) source = found.sources.insert(source, {name, lane, 0});
    if (owner.contains("result") && owner["result"].is_array())
      for (const nlohmann::json& result : owner["result"])
        if (result.is_object() && result.contains("type") && result["type"] == "timeserieslabels")
          ++source->labels;
  };
  for (const nlohmann::json& task : document) {
    if (!task.is_object()) continue;
    if (task.contains("data")) {
      const std::string recording = studio_recording_of(task["data"]);
      if (!recording.empty() &&
          std::find(recordings.begin(), recordings.end(), recording) == recordings.end())
        recordings.push_back(recording);
    }
    if (task.contains("annotations") && task["annotations"].is_array())
      for (const nlohmann::json& annotation : task["annotations"]) {
        if (!annotation.is_object()) continue;
        if (annotation.contains("was_cancelled") && annotation["was_cancelled"] == true) continue;
        const std::string user = studio_user_of(annotation);
        const std::string annotator =
            annotation.contains(kStudioAnnotatorKey) && annotation[kStudioAnnotatorKey].is_string()
                ? annotation[kStudioAnnotatorKey].get<std::string>()
                : std::string();
        const std::string name = !annotator.empty() ? annotator : user;
        const bool ground_truth =
            annotation.contains("ground_truth") && annotation["ground_truth"] == true;
        count(name,
              ground_truth ? std::string("ground-truth")
                           : "manual:" + (annotator.empty() ? "label-studio:" + user : annotator),
              annotation);
      }
    if (task.contains("predictions") && task["predictions"].is_array())
      for (const nlohmann::json& prediction : task["predictions"]) {
        if (!prediction.is_object() || !prediction.contains("model_version") ||
            !prediction["model_version"].is_string())
          continue;
        const std::string version = prediction["model_version"].get<std::string>();
        const LaneKey lane = lane_from_id(version);
        count(version, lane.source == LabelSource::kManual ? "model:" + version : version,
              prediction);
      }
  }
  for (const std::string& recording : recordings)
    found.recording += (found.recording.empty() ? "" : ",") + recording;
  return found;
}

bool is_label_studio_json(const std::string& text) {
  for (char c : text) {
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n') continue;
    if (c == '[') return true;
    break;
  }
  try {
    const nlohmann::json document = nlohmann::json::parse(text);
    return document.is_object() && !document.contains("labels") &&
           (document.contains("annotations") || document.contains("predictions"));
  } catch (const nlohmann::json::exception&) {
    return false;
  }
}

std::vector<Label> parse_label_studio(const std::string& text, const std::string& where,
                                      const InteropImport& options) {
  const nlohmann::json document = studio_tasks(text, where);
  std::vector<Label> labels;
  for (size_t t = 0; t < document.size(); ++t) {
    const nlohmann::json& task = document[t];
    const std::string task_name =
        task.is_object() && task.contains("id") && task["id"].is_number_integer()
            ? std::to_string(task["id"].get<int64_t>())
            : std::to_string(t + 1);
    const std::string at_task = where + " task " + task_name;
    if (!task.is_object()) throw Error(at_task, "not an object");
    std::string recording = options.recording;
    if (recording.empty() && task.contains("data")) recording = studio_recording_of(task["data"]);
    if (recording.empty()) throw Error(at_task, "its data names no file: give --recording");
    if (task.contains("annotations")) {
      const nlohmann::json& annotations = task["annotations"];
      if (!annotations.is_array()) throw Error(at_task, "'annotations' is not a list");
      for (size_t a = 0; a < annotations.size(); ++a) {
        const nlohmann::json& annotation = annotations[a];
        std::string at = at_task + " annotation " + std::to_string(a + 1);
        if (!annotation.is_object()) throw Error(at, "not an object");
        if (annotation.contains("id") && annotation["id"].is_number_integer())
          at = at_task + " annotation " + std::to_string(annotation["id"].get<int64_t>());
        if (annotation.contains("was_cancelled") && annotation["was_cancelled"] == true) continue;
        const bool ground_truth =
            annotation.contains("ground_truth") && annotation["ground_truth"] == true;
        const std::string user = studio_user_of(annotation);
        std::string annotator =
            annotation.contains(kStudioAnnotatorKey) && annotation[kStudioAnnotatorKey].is_string()
                ? annotation[kStudioAnnotatorKey].get<std::string>()
                : std::string();
        // --annotator maps the user (id or email) or our name to a lane.
        LaneKey lane{ground_truth ? LabelSource::kGroundTruth : LabelSource::kManual, {}};
        std::string mapped;
        if (options.annotators.count(user)) mapped = options.annotators.at(user);
        if (!annotator.empty() && options.annotators.count(annotator))
          mapped = options.annotators.at(annotator);
        // A person's name keeps the annotation's ground-truth flag; a lane id sets the lane.
        if (!mapped.empty()) {
          const LaneKey mapped_lane = lane_from_id(mapped);
          if (!(ground_truth && mapped_lane.source == LabelSource::kManual))
            lane.source = mapped_lane.source;
          if (!mapped_lane.annotator.empty()) annotator = mapped_lane.annotator;
        }
        if (annotator.empty()) annotator = user.empty() ? "" : "label-studio:" + user;
        if (annotator.empty() && lane.source != LabelSource::kGroundTruth)
          throw Error(at, "no completed_by: map it with --annotator");
        if (!annotation.contains("result")) throw Error(at, "no 'result'");
        studio_read_results(annotation["result"], at, recording, lane, annotator, std::nullopt,
                            labels);
      }
    }
    if (task.contains("predictions")) {
      const nlohmann::json& predictions = task["predictions"];
      if (!predictions.is_array()) throw Error(at_task, "'predictions' is not a list");
      for (size_t p = 0; p < predictions.size(); ++p) {
        const nlohmann::json& prediction = predictions[p];
        const std::string at = at_task + " prediction " + std::to_string(p + 1);
        if (!prediction.is_object()) throw Error(at, "not an object");
        std::string version =
            prediction.contains("model_version") && prediction["model_version"].is_string()
                ? prediction["model_version"].get<std::string>()
                : std::string();
        if (options.annotators.count(version)) version = options.annotators.at(version);
        if (version.empty()) throw Error(at, "no model_version: the model's name");
        // A prediction is a segmenter's or a model's; a bare name is a model's.
        LaneKey lane = lane_from_id(version);
        if (lane.source == LabelSource::kManual) lane = {LabelSource::kModel, version};
        std::optional<double> score;
        if (prediction.contains("score")) score = studio_number(prediction, "score", at);
        if (!prediction.contains("result")) throw Error(at, "no 'result'");
        studio_read_results(prediction["result"], at, recording, lane, lane.annotator, score,
                            labels);
      }
    }
  }
  return labels;
}

//---- The format's row (labels/label_format.h)

namespace {

class LabelStudioFormat : public LabelFormat {
 public:
  std::string name() const override { return "Label Studio"; }
  std::string flag() const override { return "--label-studio"; }
  std::string description() const override { return "Label Studio JSON"; }
  std::string extension() const override { return ".json"; }
  bool reads(const std::string& extension,
             const std::function<const std::string&()>& text) const override {
    return extension == ".json" && is_label_studio_json(text());
  }
  std::vector<Label> read(const std::string& path, const InteropImport& options) const override {
    return parse_label_studio(read_interop_text(path), path, options);
  }
  InteropSources sources(const std::string& path) const override {
    return label_studio_sources(read_interop_text(path), path);
  }
  std::string write(const std::vector<Label>& labels,
                    const std::vector<std::string>&) const override {
    return labels_label_studio(labels);
  }
};

}  // namespace

std::unique_ptr<LabelFormat> label_studio_format() { return std::make_unique<LabelStudioFormat>(); }

}  // namespace tactile
