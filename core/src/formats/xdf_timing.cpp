// The timing half of the XDF import (tactile/formats/xdf_files.h): clock offsets, the
// resampling onto the nominal rate with dropouts kept as gaps, and markers paired into labels.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

#include "tactile/error.h"
#include "tactile/formats/xdf_files.h"
#include "tactile/text.h"

namespace tactile {

namespace {

std::string xdf_marker_trimmed(const std::string& text) {
  size_t first = 0, last = text.size();
  while (first < last && std::isspace(static_cast<unsigned char>(text[first]))) ++first;
  while (last > first && std::isspace(static_cast<unsigned char>(text[last - 1]))) --last;
  return text.substr(first, last - first);
}

std::string xdf_marker_lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

// "CLASS start" -> (CLASS, +1), "CLASS end" -> (CLASS, -1), "CLASS" -> (CLASS, 0).
std::pair<std::string, int> xdf_marker_word(const std::string& text) {
  const std::string trimmed = xdf_marker_trimmed(text);
  const size_t space = trimmed.find_last_of(" \t");
  if (space == std::string::npos) return {trimmed, 0};
  const std::string word = xdf_marker_lower(trimmed.substr(space + 1));
  const std::string name = xdf_marker_trimmed(trimmed.substr(0, space));
  if (word == "start" || word == "begin") return {name, 1};
  if (word == "end") return {name, -1};
  return {trimmed, 0};
}

}  // namespace

double clock_corrected(double stamp, const std::vector<std::pair<double, double>>& offsets) {
  if (offsets.empty()) return stamp;
  if (stamp <= offsets.front().first) return stamp + offsets.front().second;
  if (stamp >= offsets.back().first) return stamp + offsets.back().second;
  const auto after = std::upper_bound(offsets.begin(), offsets.end(), stamp,
                                      [](double t, const auto& entry) { return t < entry.first; });
  const auto before = after - 1;
  const double span = after->first - before->first;
  const double weight = span > 0.0 ? (stamp - before->first) / span : 0.0;
  return stamp + before->second + weight * (after->second - before->second);
}

std::vector<size_t> xdf_clock_resets(const std::vector<std::pair<double, double>>& offsets) {
  std::vector<size_t> resets;
  if (offsets.size() < 3) return resets;  // no usual interval to tell a jump from
  std::vector<double> intervals, changes;
  for (size_t k = 1; k < offsets.size(); ++k) {
    intervals.push_back(offsets[k].first - offsets[k - 1].first);
    changes.push_back(std::abs(offsets[k].second - offsets[k - 1].second));
  }
  const auto median = [](std::vector<double> values) {
    const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    return *middle;
  };
  const double usual_interval = median(intervals), usual_change = median(changes);
  for (size_t k = 0; k < intervals.size(); ++k) {
    const bool time_jumps = intervals[k] < 0.0 || intervals[k] - usual_interval > kXdfResetSeconds;
    const bool offset_jumps = changes[k] - usual_change > kXdfResetOffsetSeconds;
    if (time_jumps && offset_jumps) resets.push_back(k + 1);
  }
  return resets;
}

std::vector<double> clock_corrected_stamps(const std::vector<double>& stamps,
                                           const std::vector<std::pair<double, double>>& offsets) {
  if (offsets.empty()) return stamps;
  // The measurements between resets, each segment by collection time (clock_corrected's order).
  std::vector<size_t> starts = xdf_clock_resets(offsets);
  starts.insert(starts.begin(), 0);
  std::vector<std::vector<std::pair<double, double>>> segments;
  for (size_t k = 0; k < starts.size(); ++k) {
    const size_t end = k + 1 < starts.size() ? starts[k + 1] : offsets.size();
    segments.emplace_back(offsets.begin() + static_cast<std::ptrdiff_t>(starts[k]),
                          offsets.begin() + static_cast<std::ptrdiff_t>(end));
    std::stable_sort(segments.back().begin(), segments.back().end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
  }
  // How far a stamp lies from a segment's measurements (0 inside their span).
  const auto distance = [&](double stamp, size_t segment) {
    const double first = segments[segment].front().first, last = segments[segment].back().first;
    return stamp < first ? first - stamp : (stamp > last ? stamp - last : 0.0);
  };
  std::vector<double> corrected(stamps.size());
  size_t segment = 0;
  for (size_t k = 0; k < stamps.size(); ++k) {
    bool stepped = false;  // one jump of the stamps is one reset
    // Samples come in the order they were sent, so the segment only moves on: at the sample
    // whose stamp jumps as the offsets did at the reset (the clock jumps by minus the offset's
    // jump), or once a stamp lies nearer the next segment's measurements (a stream without
    // samples across the reset).
    while (segment + 1 < segments.size()) {
      const double jump = segments[segment + 1].front().second - segments[segment].back().second;
      const double step = k > 0 ? stamps[k] - stamps[k - 1] : 0.0;
      const bool steps_with_reset =
          !stepped && step * jump < 0.0 && std::abs(step) > 0.5 * std::abs(jump);
      if (!steps_with_reset && !(distance(stamps[k], segment + 1) < distance(stamps[k], segment)))
        break;
      stepped = stepped || steps_with_reset;
      ++segment;
    }
    corrected[k] = clock_corrected(stamps[k], segments[segment]);
  }
  return corrected;
}

SampleMatrix resample_to_rate(const std::vector<double>& stamps, const SampleMatrix& samples,
                              double rate_hz, const std::string& where) {
  const auto count = static_cast<int64_t>(stamps.size());
  if (count == 0 || samples.rows() != count) throw Error(where, "has no samples");
  for (int64_t k = 1; k < count; ++k)
    if (stamps[static_cast<size_t>(k)] < stamps[static_cast<size_t>(k - 1)])
      throw Error(where, "sample " + std::to_string(k) + "'s time stamp " +
                             shortest_text(stamps[static_cast<size_t>(k)]) + " is before sample " +
                             std::to_string(k - 1) + "'s " +
                             shortest_text(stamps[static_cast<size_t>(k - 1)]));
  const double step = 1.0 / rate_hz;
  const double span = stamps.back() - stamps.front();
  // Dropouts make the grid longer than the samples; one far longer is a file that lies about
  // its rate or its stamps: refused before anything is allocated.
  const double limit = 8.0 * static_cast<double>(count) + 1000.0;
  if (!(span * rate_hz + 1.0 < limit))
    throw Error(where, "time stamps span " + shortest_text(span) + " s: at " +
                           shortest_text(rate_hz) +
                           " Hz that is more than 8 grid points per sample held (" +
                           std::to_string(count) + ")");
  // The grid runs to the point nearest the last stamp, so every sample has its point: clock
  // offsets that drift shorten a span of N steps by microseconds (N - 1e-4 steps), and a grid
  // cut at the last whole step before the last stamp lost the last sample to that rounding.
  // A point past the last stamp (by under half a step) takes the last sample, below; a last
  // stamp half way between two points ends the grid at the first.
  const auto points = static_cast<int64_t>(std::ceil(span * rate_hz - 0.5)) + 1;
  SampleMatrix out(points, samples.cols());
  const double largest_step = 1.5 * step;
  int64_t below = 0;  // the last sample at or before the grid point
  for (int64_t k = 0; k < points; ++k) {
    const double t = stamps.front() + static_cast<double>(k) * step;
    while (below + 1 < count && stamps[static_cast<size_t>(below + 1)] <= t) ++below;
    const double t0 = stamps[static_cast<size_t>(below)];
    if (t == t0 || below + 1 >= count) {
      // On a sample, or past the last one by rounding only.
      out.row(k) = samples.row(below);
      continue;
    }
    const double t1 = stamps[static_cast<size_t>(below + 1)];
    if (t1 - t0 > largest_step) {
      out.row(k).setConstant(std::numeric_limits<float>::quiet_NaN());
      continue;
    }
    const auto weight = static_cast<float>((t - t0) / (t1 - t0));
    out.row(k) = samples.row(below) + weight * (samples.row(below + 1) - samples.row(below));
  }
  return out;
}

XdfMarkerLabels labels_from_markers(const std::vector<XdfMarker>& markers, double end_time,
                                    double sample_seconds, const std::string& where) {
  XdfMarkerLabels result;
  auto marker_text = [](const XdfMarker& marker) {
    return in_quotes(printable_text(marker.text)) + " at " + shortest_text(marker.time) + " s";
  };
  // The label opened by marker `opened`, clipped to the data [0, end_time). One shorter than a
  // sample holds no sample of the data: a marker at the data's end made [0.8999999999999986,
  // 0.9) of a 0.9-s recording, a label ELAN cannot hold. It is dropped and said in `dropped`.
  // A millionth of a sample absorbs the rounding of marker times (a difference of two stamps).
  auto add = [&](size_t opened, const std::string& name, double t0, double t1) {
    const std::string named =
        "marker " + std::to_string(opened) + " " + marker_text(markers[opened]);
    t0 = std::max(t0, 0.0);
    t1 = std::min(t1, end_time);
    if (t0 >= end_time) {
      result.dropped.push_back(named + ": at or after the data's end (" + shortest_text(end_time) +
                               " s)");
      return;
    }
    if (t1 <= 0.0) {
      result.dropped.push_back(named + ": its label ends before the data's first sample");
      return;
    }
    if (t1 - t0 < sample_seconds * (1.0 - 1e-6)) {
      result.dropped.push_back(named + ": its label [" + shortest_text(t0) + ", " +
                               shortest_text(t1) + ") is shorter than one sample (" +
                               shortest_text(sample_seconds) + " s)");
      return;
    }
    Label label;
    label.t0 = t0;
    label.t1 = t1;
    label.region = "all";
    label.class_name = name;
    label.annotator = "import";
    label.source = LabelSource::kGroundTruth;
    result.labels.push_back(std::move(label));
  };
  // The open label: its class, its start, and whether a "start" opened it (index into markers).
  std::string open_class;
  double open_time = 0.0;
  int64_t open_start = -1;  // the "start" marker, -1 for a plain one
  size_t open_marker = 0;   // the marker that opened it, whichever kind
  bool open = false;
  for (size_t k = 0; k < markers.size(); ++k) {
    const XdfMarker& marker = markers[k];
    const auto [name, kind] = xdf_marker_word(marker.text);
    const std::string place = where + " marker " + std::to_string(k);
    if (open && open_start >= 0) {
      const XdfMarker& start = markers[static_cast<size_t>(open_start)];
      if (kind != -1 || name != open_class)
        throw Error(place, marker_text(marker) + " inside " + marker_text(start) +
                               ", which only \"" + open_class + " end\" closes");
      add(open_marker, open_class, open_time, marker.time);
      open = false;
      continue;
    }
    if (kind == -1) throw Error(place, marker_text(marker) + " ends no \"" + name + " start\"");
    if (open) add(open_marker, open_class, open_time, marker.time);
    open = !name.empty() && xdf_marker_lower(name) != "none";
    open_class = name;
    open_time = marker.time;
    open_marker = k;
    open_start = kind == 1 ? static_cast<int64_t>(k) : -1;
    if (kind == 1 && !open) throw Error(place, marker_text(marker) + " starts no class");
  }
  if (open && open_start >= 0)
    throw Error(where + " marker " + std::to_string(open_start),
                marker_text(markers[static_cast<size_t>(open_start)]) + " is never ended");
  if (open) add(open_marker, open_class, open_time, end_time);
  return result;
}

}  // namespace tactile
