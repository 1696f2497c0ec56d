// Label Studio's JSON export of time-series labels both ways (elan_and_label_studio.h): a list of
// tasks, each with annotations (people; "ground_truth": true for ground truth) and predictions
// (segmenters and models), each holding "timeserieslabels" results with start and end.
//
// What Label Studio 1.x writes and reads, from its source (label_studio/tasks/serializers.py):
// its import takes completed_by as a member's user id (a number) or {"email": ...}, refuses any
// other, and gives an annotation without one to the user who imports; of an annotation it keeps
// result, ground_truth, was_cancelled, lead_time and completed_by only (our tactile_annotator
// does not come back from it; a result's own keys are kept as they are).
#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <tuple>
#include <utility>

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

// A TimeSeries whose time column holds dates gives start and end in milliseconds since 1970
// (1592250751951.8 in Label Studio's documented example). No recording lasts 1e11 s (3000
// years), and a Unix time in seconds stays below it until the year 5138: a value from here on
// is epoch milliseconds, and a time in seconds must stay below it.
constexpr double kEpochMillisecondsFrom = 1e11;

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

// What a result is to us: the span of a TimeSeries ("timeserieslabels": seconds, or epoch
// milliseconds for a time column of dates) or of an Audio ("labels" in seconds, as Label Studio
// writes an audio region: start, end, channel, labels), or nothing we import. `left_out` then
// says what it is, for the count of what an import left out.
enum class StudioSpan { kTimeSeries, kAudio, kOther };

StudioSpan studio_span_of(const nlohmann::json& result, std::string* left_out = nullptr) {
  const std::string type = result.contains("type") && result["type"].is_string()
                               ? result["type"].get<std::string>()
                               : std::string();
  if (type == "timeserieslabels") return StudioSpan::kTimeSeries;
  const nlohmann::json* value =
      result.contains("value") && result["value"].is_object() ? &result["value"] : nullptr;
  // A Labels control over a Text or HyperText gives character offsets (with the text), not
  // times.
  const bool text = value && (value->contains("text") || value->contains("startOffset"));
  if (type == "labels" && !text) return StudioSpan::kAudio;
  if (left_out) {
    *left_out = type.empty() ? std::string("result without a type") : type;
    if (result.contains("from_name") && result["from_name"].is_string())
      *left_out += " from '" + result["from_name"].get<std::string>() + "'";
    if (text) *left_out += " (spans of a text, not of time)";
    if (type == "timelinelabels") *left_out += " (video frames, not seconds)";
  }
  return StudioSpan::kOther;
}

// The first time value of a task that holds its time series (valueType="json": columns of
// values under a data key): the first value of a column of epoch milliseconds. None when no
// column starts there, or columns start at different times.
std::optional<double> studio_first_time_ms(const nlohmann::json& data) {
  std::optional<double> first;
  bool differ = false;
  auto look = [&](const nlohmann::json& columns) {
    for (const auto& [key, column] : columns.items()) {
      if (!column.is_array() || column.empty() || !column[0].is_number()) continue;
      const double value = column[0].get<double>();
      if (!std::isfinite(value) || value < kEpochMillisecondsFrom) continue;
      if (first && *first != value) differ = true;
      first = value;
    }
  };
  if (!data.is_object()) return std::nullopt;
  look(data);
  for (const auto& [key, value] : data.items())
    if (value.is_object()) look(value);
  if (differ) return std::nullopt;
  return first;
}

// One task's times: epoch milliseconds placed on the recording's clock, from the first that
// is known of --start-ms, the recording's own start, the task's first time value.
class StudioTaskTime {
 public:
  StudioTaskTime(const InteropImport& options, std::string recording, const nlohmann::json* data)
      : options_(options), recording_(std::move(recording)), data_(data) {}

  // A result's start and end in seconds on the recording's clock.
  std::pair<double, double> span(const nlohmann::json& value, StudioSpan kind,
                                 const std::string& at) {
    double start = studio_number(value, "start", at), end = studio_number(value, "end", at);
    const bool start_ms = start >= kEpochMillisecondsFrom, end_ms = end >= kEpochMillisecondsFrom;
    if (kind == StudioSpan::kTimeSeries && (start_ms || end_ms)) {
      if (start_ms != end_ms)
        throw Error(at, "start " + shortest_text(start) + " and end " + shortest_text(end) +
                            " are not both epoch milliseconds");
      const double origin = origin_ms(start, at);
      start = first_sample_ + (start - origin) / 1000.0;
      end = first_sample_ + (end - origin) / 1000.0;
    }
    for (const double seconds : {start, end})
      if (!(std::abs(seconds) < kEpochMillisecondsFrom))
        throw Error(at, "a time of " + shortest_text(seconds) +
                            " s is beyond any recording (times are seconds" +
                            (kind == StudioSpan::kAudio ? " of the audio)" : ")"));
    return {start, end};
  }

 private:
  double origin_ms(double start, const std::string& at) {
    if (!resolved_) {
      resolved_ = true;
      RecordingClock clock;
      if (options_.clock) clock = options_.clock(recording_);
      if (clock.found) first_sample_ = clock.first_sample;
      if (options_.start_ms) {
        origin_ = *options_.start_ms;
      } else if (clock.start_ms) {
        origin_ = *clock.start_ms;
      } else if (data_) {
        origin_ = studio_first_time_ms(*data_);
      }
      if (clock.found)
        unknown_ = clock.file + " " + clock.missing;
      else if (!clock.file.empty())
        unknown_ = "no " + clock.file;
      else
        unknown_ = "no recording file was looked for";
      if (!origin_) unknown_ += ", and the task's data holds no column of epoch milliseconds";
    }
    if (!origin_)
      throw Error(at, "start " + shortest_text(start) +
                          " is in epoch milliseconds (a TimeSeries whose time column holds "
                          "dates), and the start of recording '" +
                          recording_ + "' is not known (" + unknown_ +
                          "): give --start-ms, the Unix time in milliseconds of its first "
                          "sample");
    return *origin_;
  }

  const InteropImport& options_;
  std::string recording_;
  const nlohmann::json* data_;
  bool resolved_ = false;
  std::optional<double> origin_;
  double first_sample_ = 0.0;
  std::string unknown_;
};

// The labels of one annotation's or prediction's results; results that are no time span are
// counted in `left_out` by kind.
void studio_read_results(const nlohmann::json& results, const std::string& at_owner,
                         const std::string& recording, const LaneKey& lane,
                         const std::string& annotator, std::optional<double> owner_score,
                         StudioTaskTime& time, std::map<std::string, size_t>& left_out,
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
    // Other controls of the project (choices, text areas, boxes) are not labels: counted.
    std::string kind_name;
    const StudioSpan kind = studio_span_of(result, &kind_name);
    if (kind == StudioSpan::kOther) {
      ++left_out[kind_name];
      continue;
    }
    if (!result.contains("value") || !result["value"].is_object()) throw Error(at, "no 'value'");
    const nlohmann::json& value = result["value"];
    if (value.contains("instant") && value["instant"].is_boolean() && value["instant"].get<bool>())
      throw Error(at, "an instant, not a span: a label needs a start and an end");
    Label label;
    label.recording = recording;
    std::tie(label.t0, label.t1) = time.span(value, kind, at);
    if (!(label.t1 > label.t0))
      throw Error(at, "ends at " + shortest_text(label.t1) + " s, not after its start " +
                          shortest_text(label.t0) + " s");
    const char* names = kind == StudioSpan::kTimeSeries ? "timeserieslabels" : "labels";
    if (!value.contains(names) || !value[names].is_array() || value[names].size() != 1 ||
        !value[names][0].is_string())
      throw Error(at, std::string("'") + names + "' must hold exactly one label name");
    label.class_name = value[names][0].get<std::string>();
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

std::string labels_label_studio(const std::vector<Label>& labels, const InteropExport& options) {
  // The people's names (ground truth and manual lanes), each member's completed_by.
  std::set<std::string> people;
  for (const Label& label : labels) {
    if (label.source == LabelSource::kGroundTruth || label.source == LabelSource::kManual)
      people.insert(label.annotator);
    // Label Studio's reader (ours too) takes a time from 1e11 on for epoch milliseconds.
    for (const double seconds : {label.t0, label.t1})
      if (!(std::abs(seconds) < kEpochMillisecondsFrom))
        throw Error("Label Studio export label " + std::to_string(label.id),
                    "a time of " + shortest_text(seconds) +
                        " s: Label Studio reads a time past 1e11 as epoch milliseconds");
  }
  std::map<std::string, nlohmann::json> completed_by;
  for (const auto& [name, member] : options.members) {
    if (!people.count(name))
      throw Error("--member", "'" + name + "' is no annotator of the labels exported (" +
                                  joined({people.begin(), people.end()}) + ")");
    const bool id =
        !member.empty() && member.size() <= 18 &&
        std::all_of(member.begin(), member.end(), [](char c) { return c >= '0' && c <= '9'; });
    const size_t at = member.find('@');
    if (id)
      completed_by[name] = std::stoll(member);
    else if (at != std::string::npos && at > 0 && at + 1 < member.size() &&
             member.find_first_of(" \t\r\n") == std::string::npos)
      completed_by[name] = {{"email", member}};
    else
      throw Error("--member", "'" + name + "=" + member +
                                  "': a member is a Label Studio user id (a number) or e-mail");
  }
  // Per recording, per lane and (for ground truth) per annotator: one annotation or prediction.
  std::map<std::string, std::vector<Label>> by_recording;
  for (const Label& label : labels) by_recording[label.recording].push_back(label);
  nlohmann::json tasks = nlohmann::json::array();
  size_t next_result = 1;
  int64_t next_annotation = 1;
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
        // completed_by only for a project member: Label Studio refuses any other.
        nlohmann::json annotation{{"id", next_annotation++}};
        if (completed_by.count(annotator)) annotation["completed_by"] = completed_by[annotator];
        annotation[kStudioAnnotatorKey] = annotator;
        annotation["ground_truth"] = key.source == LabelSource::kGroundTruth;
        annotation["was_cancelled"] = false;
        annotation["result"] = std::move(list);
        annotations.push_back(std::move(annotation));
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
        if (result.is_object() && studio_span_of(result) != StudioSpan::kOther) ++source->labels;
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
        // Without completed_by nor our name: "none", to be mapped (no lane of its own).
        const std::string name = !annotator.empty() ? annotator
                                 : !user.empty()    ? user
                                                    : std::string(kStudioNoUser);
        const bool ground_truth =
            annotation.contains("ground_truth") && annotation["ground_truth"] == true;
        std::string lane = "manual:" + (annotator.empty() ? "label-studio:" + user : annotator);
        if (ground_truth) lane = "ground-truth";
        if (!ground_truth && annotator.empty() && user.empty()) lane.clear();
        count(name, lane, annotation);
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
                                      const InteropImport& options,
                                      std::vector<std::string>* left_out) {
  const nlohmann::json document = studio_tasks(text, where);
  std::vector<Label> labels;
  std::map<std::string, size_t> others;  // results that are no time span, by kind
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
    StudioTaskTime time(options, recording, task.contains("data") ? &task["data"] : nullptr);
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
        // --annotator maps the user (id or email) or our name to a lane; "none" an annotation
        // with neither (Label Studio's example tasks have no completed_by).
        LaneKey lane{ground_truth ? LabelSource::kGroundTruth : LabelSource::kManual, {}};
        std::string mapped;
        if (!user.empty() && options.annotators.count(user)) mapped = options.annotators.at(user);
        if (!annotator.empty() && options.annotators.count(annotator))
          mapped = options.annotators.at(annotator);
        const bool nobody = user.empty() && annotator.empty();
        if (nobody && options.annotators.count(kStudioNoUser))
          mapped = options.annotators.at(kStudioNoUser);
        // A person's name keeps the annotation's ground-truth flag; a lane id sets the lane.
        if (!mapped.empty()) {
          const LaneKey mapped_lane = lane_from_id(mapped);
          if (!(ground_truth && mapped_lane.source == LabelSource::kManual))
            lane.source = mapped_lane.source;
          if (!mapped_lane.annotator.empty()) annotator = mapped_lane.annotator;
        }
        if (annotator.empty()) annotator = user.empty() ? "" : "label-studio:" + user;
        if (annotator.empty() && lane.source != LabelSource::kGroundTruth)
          throw Error(at, std::string("no completed_by: map it with --annotator ") + kStudioNoUser +
                              "=NAME (a name, or a lane: ground-truth, model:NAME, ...)");
        if (!annotation.contains("result")) throw Error(at, "no 'result'");
        studio_read_results(annotation["result"], at, recording, lane, annotator, std::nullopt,
                            time, others, labels);
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
        studio_read_results(prediction["result"], at, recording, lane, lane.annotator, score, time,
                            others, labels);
      }
    }
  }
  std::vector<std::string> kinds;
  size_t count = 0;
  for (const auto& [kind, results] : others) {
    kinds.push_back(std::to_string(results) + " " + kind);
    count += results;
  }
  // A file of other controls only is not taken for one without labels.
  if (labels.empty() && count > 0)
    throw Error(where, "no time spans, only " + std::to_string(count) +
                           (count == 1 ? " result" : " results") + " of other controls (" +
                           joined(kinds) +
                           "): a label is a TimeSeriesLabels span or an Audio Labels region");
  if (left_out) left_out->insert(left_out->end(), kinds.begin(), kinds.end());
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
  std::vector<Label> read(const std::string& path, const InteropImport& options,
                          std::vector<std::string>& left_out) const override {
    return parse_label_studio(read_interop_text(path), path, options, &left_out);
  }
  InteropSources sources(const std::string& path) const override {
    return label_studio_sources(read_interop_text(path), path);
  }
  std::string write(const std::vector<Label>& labels, const std::vector<std::string>&,
                    const InteropExport& options) const override {
    return labels_label_studio(labels, options);
  }
};

}  // namespace

std::unique_ptr<LabelFormat> label_studio_format() { return std::make_unique<LabelStudioFormat>(); }

}  // namespace tactile
