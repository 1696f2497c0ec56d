#include "tactile/labels/label_file_commands.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "tactile/error.h"
#include "tactile/io/atomic_file.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labels/label_format.h"
#include "tactile/labels/lanes.h"
#include "tactile/text.h"

namespace tactile {

namespace {

// printf's formatting into a string: the agreement report keeps the columns it always had.
std::string formatted_line(const char* format, ...) {
  va_list arguments;
  va_start(arguments, format);
  va_list again;
  va_copy(again, arguments);
  const int size = std::vsnprintf(nullptr, 0, format, arguments);
  va_end(arguments);
  std::string text(static_cast<size_t>(std::max(size, 0)) + 1, '\0');
  std::vsnprintf(text.data(), text.size(), format, again);
  va_end(again);
  text.resize(static_cast<size_t>(std::max(size, 0)));
  return text;
}

// A lane as --a / --b name it: "ground-truth", "manual:NAME" (or just NAME),
// "segmenter:METHOD", "model:NAME".
std::vector<Label> labels_of_lane(const LabelStore& store, const std::string& recording,
                                  const std::string& lane, const char* option) {
  std::string id = lane;
  if (lane != "ground-truth" && lane.find(':') == std::string::npos) id = "manual:" + lane;
  // The form lane ids had before they followed the documentation.
  if (lane.starts_with("segmenter:segmenter:")) id = lane.substr(10);
  LabelFilter filter;
  if (!recording.empty()) filter.recording = recording;
  std::vector<Label> labels;
  for (const Label& label : store.list(filter))
    if (lane_of(label).id() == id) labels.push_back(label);
  if (labels.empty()) throw Error(option, "no labels in lane '" + id + "' of " + store.path());
  return labels;
}

// days since 1970-01-01 of a date of the proleptic Gregorian calendar (Howard Hinnant's
// days_from_civil).
int64_t days_from_civil(int64_t year, int64_t month, int64_t day) {
  year -= month <= 2;
  const int64_t era = (year >= 0 ? year : year - 399) / 400;
  const int64_t year_of_era = year - era * 400;
  const int64_t day_of_year = (153 * (month + (month > 2 ? -3 : 9)) + 2) / 5 + day - 1;
  const int64_t day_of_era = year_of_era * 365 + year_of_era / 4 - year_of_era / 100 + day_of_year;
  return era * 146097 + day_of_era - 719468;
}

}  // namespace

std::optional<double> unix_milliseconds(const std::string& text) {
  // YYYY-MM-DD(T| )hh:mm:ss[.fraction](Z|+hh:mm|-hh:mm|+hhmm|-hhmm)
  size_t at = 0;
  auto digits = [&](size_t count, int64_t& value) {
    if (at + count > text.size()) return false;
    value = 0;
    for (size_t k = 0; k < count; ++k) {
      const char c = text[at + k];
      if (c < '0' || c > '9') return false;
      value = value * 10 + (c - '0');
    }
    at += count;
    return true;
  };
  auto literal = [&](const char* options) {
    if (at >= text.size() || text[at] == '\0' || !std::strchr(options, text[at])) return false;
    ++at;
    return true;
  };
  int64_t year = 0, month = 0, day = 0, hour = 0, minute = 0, second = 0;
  if (!digits(4, year) || !literal("-") || !digits(2, month) || !literal("-") || !digits(2, day) ||
      !literal("T ") || !digits(2, hour) || !literal(":") || !digits(2, minute) || !literal(":") ||
      !digits(2, second))
    return std::nullopt;
  double fraction = 0.0;
  if (at < text.size() && (text[at] == '.' || text[at] == ',')) {
    ++at;
    double scale = 0.1;
    const size_t first = at;
    while (at < text.size() && text[at] >= '0' && text[at] <= '9') {
      fraction += scale * (text[at] - '0');
      scale /= 10.0;
      ++at;
    }
    if (at == first) return std::nullopt;
  }
  int64_t offset_minutes = 0;
  if (literal("Zz")) {
  } else if (at < text.size() && (text[at] == '+' || text[at] == '-')) {
    const int sign = text[at] == '-' ? -1 : 1;
    ++at;
    int64_t hours = 0, minutes = 0;
    if (!digits(2, hours)) return std::nullopt;
    if (at < text.size() && text[at] == ':') ++at;
    if (!digits(2, minutes) || hours > 23 || minutes > 59) return std::nullopt;
    offset_minutes = sign * (hours * 60 + minutes);
  } else {
    return std::nullopt;  // no zone: a local time of somewhere
  }
  if (at != text.size()) return std::nullopt;
  if (month < 1 || month > 12 || day < 1 || day > 31 || hour > 23 || minute > 59 || second > 60)
    return std::nullopt;
  const int64_t seconds = days_from_civil(year, month, day) * 86400 + hour * 3600 + minute * 60 +
                          second - offset_minutes * 60;
  return static_cast<double>(seconds) * 1000.0 + fraction * 1000.0;
}

LabelSource label_source_option(const std::string& text, const std::string& option) {
  try {
    return parse_label_source(text);
  } catch (const Error& error) {
    throw Error(option, error.message());
  }
}

std::vector<std::string> damage_lines(const LabelStore& store) {
  std::vector<std::string> lines;
  for (const StoreProblem& problem : store.problems())
    lines.push_back(problem.where(store.path()) + ": " + problem.what);
  return lines;
}

LabelExport export_label_file(const std::string& database, const std::string& out,
                              const std::string& format, const LabelFilter& filter,
                              const std::vector<std::string>& vocabulary,
                              const InteropExport& interop) {
  const LabelFormat* chosen = label_format_named(format);
  if (!chosen) {
    std::vector<std::string> names;
    for (const LabelFormat* known : label_formats()) names.push_back(known->name());
    throw Error("format", in_quotes(format) + " is not a label format (" + joined(names) + ")");
  }
  const LabelStore store(database, LabelStore::OpenMode::kExisting);
  const std::vector<Label> labels = store.list(filter);
  write_file_atomically(out, chosen->write(labels, vocabulary, interop),
                        chosen->name() + " export");
  LabelExport written;
  written.labels = labels.size();
  written.damaged = damage_lines(store);
  return written;
}

InteropSources interop_sources(const std::string& file) {
  return label_format_of(file).sources(file);
}

RecordingClock recording_clock(const std::string& folder, const std::string& recording) {
  RecordingClock clock;
  const std::filesystem::path file = std::filesystem::path(folder) / (recording + ".h5");
  clock.file = file.string();
  std::error_code error;
  if (recording.empty() || !std::filesystem::exists(file, error)) return clock;
  const RecordingFile opened(clock.file);
  clock.found = true;
  if (opened.streams().empty()) {
    clock.missing = "has no stream";
    return clock;
  }
  // The first stream's first sample, as `labels agreement` takes a recording's span.
  const StreamInfo& stream = opened.streams().front();
  clock.first_sample = stream.has_timestamps ? stream.first_timestamp : stream.start_time;
  // A clock at 1e9 s or later (2001-09-09) counts from 1970: nothing else runs that long.
  if (clock.first_sample >= 1e9) {
    clock.start_ms = clock.first_sample * 1000.0;
    return clock;
  }
  const auto start = opened.metadata().find("start_time");
  if (start == opened.metadata().end()) {
    clock.missing = "starts at " + shortest_text(clock.first_sample) +
                    " s on a clock of its own and has no start_time";
    return clock;
  }
  clock.start_ms = unix_milliseconds(start->second);
  if (!clock.start_ms)
    clock.missing = "has start_time '" + start->second +
                    "', not an ISO 8601 date-time with a time zone (EDF gives the recorder's "
                    "local time, which names none)";
  return clock;
}

std::map<std::string, RecordingSpan> recording_spans(const std::vector<Label>& labels,
                                                     const std::string& folder) {
  std::map<std::string, RecordingSpan> spans;
  std::set<std::string> missing;
  for (const Label& label : labels) {
    if (spans.count(label.recording) || missing.count(label.recording)) continue;
    const std::filesystem::path path = std::filesystem::path(folder) / (label.recording + ".h5");
    std::error_code error;
    if (std::filesystem::exists(path, error))
      spans[label.recording] = recording_span(path.string());
    else
      missing.insert(label.recording);
  }
  return spans;
}

namespace {

// Whether the store's `held` is the same label as `label` from a file: ids, revisions and
// times of writing are the store's own; times within a microsecond (a file's rounding).
bool same_label(const Label& held, const Label& label) {
  return held.recording == label.recording && std::abs(held.t0 - label.t0) < 1e-6 &&
         std::abs(held.t1 - label.t1) < 1e-6 && held.region == label.region &&
         held.class_name == label.class_name && held.annotator == label.annotator &&
         held.source == label.source && std::abs(held.confidence - label.confidence) < 1e-9 &&
         held.note == label.note;
}

}  // namespace

LabelImport import_label_file(const std::string& database, const std::string& file,
                              const InteropImport& options) {
  const std::string folder = !options.recordings.empty()
                                 ? options.recordings
                                 : std::filesystem::path(database).parent_path().string();
  InteropImport reading = options;
  if (!reading.clock)
    reading.clock = [folder](const std::string& recording) {
      return recording_clock(folder, recording);
    };
  // All or nothing: the file is read and checked whole, then added in one transaction.
  LabelImport imported;
  const std::vector<Label> labels = label_format_of(file).read(file, reading, imported.left_out);
  const std::map<std::string, RecordingSpan> spans = recording_spans(labels, folder);
  for (const Label& label : labels) {
    const auto span = spans.find(label.recording);
    if (span == spans.end()) continue;
    const SpanProblem problem = span_problem(label, span->second);
    if (!problem.kind.empty())
      throw Error(file,
                  "recording " + label.recording + ": " + problem.what + "; nothing imported");
  }
  LabelStore store(database);
  std::map<std::string, std::vector<Label>> held;
  std::vector<Label> added;
  for (const Label& label : labels) {
    if (!held.count(label.recording)) {
      LabelFilter filter;
      filter.recording = label.recording;
      held[label.recording] = store.list(filter);
    }
    const std::vector<Label>& there = held[label.recording];
    if (std::any_of(there.begin(), there.end(),
                    [&](const Label& other) { return same_label(other, label); }))
      ++imported.already;
    else
      added.push_back(label);
  }
  if (!added.empty()) store.add_many(added);
  imported.added = added.size();
  return imported;
}

std::string imported_labels_line(const LabelImport& imported, const std::string& database) {
  std::string line = "imported " + std::to_string(imported.added) +
                     (imported.added == 1 ? " label" : " labels") + " into " + database;
  if (imported.already > 0)
    line += "; " + std::to_string(imported.already) + " already there, not added again";
  if (!imported.left_out.empty())
    line += "; left out what is no time span: " + joined(imported.left_out);
  return line;
}

AgreementReport lane_agreement(const AgreementQuery& query,
                               const std::function<void(double)>& step) {
  const LabelStore store(query.database, LabelStore::OpenMode::kExisting);
  const std::vector<Label> a = labels_of_lane(store, query.recording, query.a, "--a");
  const std::vector<Label> b = labels_of_lane(store, query.recording, query.b, "--b");
  const std::vector<std::string> damaged = damage_lines(store);
  if (step) step(0.3);
  // Each recording's span and rate from its file, when it is in the folder.
  const std::filesystem::path folder = query.recordings.empty()
                                           ? std::filesystem::path(query.database).parent_path()
                                           : std::filesystem::path(query.recordings);
  std::map<std::string, RecordingTiming> timing;
  for (const auto* labels : {&a, &b})
    for (const Label& label : *labels) {
      if (timing.count(label.recording)) continue;
      const std::filesystem::path file = folder / (label.recording + ".h5");
      std::error_code error;
      if (!std::filesystem::exists(file, error)) continue;
      const RecordingFile recording(file.string());
      if (recording.streams().empty()) continue;
      const StreamInfo& stream = recording.streams().front();
      const double start = stream.has_timestamps ? stream.first_timestamp : stream.start_time;
      timing[label.recording] = {start, start + stream.duration(), stream.rate_hz};
    }
  if (step) step(0.6);
  return {query, compute_agreement(a, b, timing, query.iou), damaged};
}

std::string agreement_text(const AgreementReport& report) {
  const Agreement& agreement = report.agreement;
  const AgreementQuery& query = report.query;
  std::string text;
  text += formatted_line("A: %s (%lld labels)   B: %s (%lld labels)\n", query.a.c_str(),
                         static_cast<long long>(agreement.a_segments), query.b.c_str(),
                         static_cast<long long>(agreement.b_segments));
  text += formatted_line("kappa over time: %.3f (observed %.3f, chance %.3f, %lld samples)\n",
                         agreement.kappa, agreement.observed, agreement.expected,
                         static_cast<long long>(agreement.samples));
  text += formatted_line(
      "segments at IoU >= %.2f: precision %.3f, recall %.3f, F1 %.3f (%lld matched)\n", query.iou,
      agreement.precision, agreement.recall, agreement.f1,
      static_cast<long long>(agreement.matched));
  text += formatted_line("classes of matched segments (rows A, columns B):\n%12s", "");
  for (const std::string& name : agreement.classes)
    text += formatted_line(" %10.10s", name.c_str());
  text += "\n";
  for (size_t row = 0; row < agreement.classes.size(); ++row) {
    text += formatted_line("%12.12s", agreement.classes[row].c_str());
    for (int64_t count : agreement.confusion[row])
      text += formatted_line(" %10lld", static_cast<long long>(count));
    text += "\n";
  }
  text += formatted_line("%zu disagreements\n", agreement.disagreements.size());
  for (const Disagreement& d : agreement.disagreements) {
    std::string what;
    if (d.kind == "class") what = "class " + d.a_class + " vs " + d.b_class;
    if (d.kind == "missed") what = "only in A: " + d.a_class;
    if (d.kind == "extra") what = "only in B: " + d.b_class;
    text += formatted_line("  %s %.3f-%.3f s: %s\n", d.recording.c_str(), d.t0, d.t1, what.c_str());
  }
  return text;
}

std::string agreement_json(const AgreementReport& report) {
  const Agreement& agreement = report.agreement;
  nlohmann::json disagreements = nlohmann::json::array();
  for (const Disagreement& d : agreement.disagreements)
    disagreements.push_back({{"recording", d.recording},
                             {"t0", d.t0},
                             {"t1", d.t1},
                             {"a", d.a_class},
                             {"b", d.b_class},
                             {"kind", d.kind}});
  return nlohmann::json{{"a", report.query.a},
                        {"b", report.query.b},
                        {"kappa", agreement.kappa},
                        {"observed", agreement.observed},
                        {"expected", agreement.expected},
                        {"samples", agreement.samples},
                        {"iou", report.query.iou},
                        {"a_segments", agreement.a_segments},
                        {"b_segments", agreement.b_segments},
                        {"matched", agreement.matched},
                        {"precision", agreement.precision},
                        {"recall", agreement.recall},
                        {"f1", agreement.f1},
                        {"classes", agreement.classes},
                        {"confusion", agreement.confusion},
                        {"disagreements", disagreements}}
             .dump(2) +
         "\n";
}

}  // namespace tactile
