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
  // 1e-9 of a step absorbs the rounding of stamps that sit on the grid.
  const auto points = static_cast<int64_t>(std::floor(span * rate_hz + 1e-9)) + 1;
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

std::vector<Label> labels_from_markers(const std::vector<XdfMarker>& markers, double end_time,
                                       const std::string& where) {
  std::vector<Label> labels;
  auto add = [&](const std::string& name, double t0, double t1) {
    t0 = std::max(t0, 0.0);
    t1 = std::min(t1, end_time);
    if (!(t1 > t0)) return;
    Label label;
    label.t0 = t0;
    label.t1 = t1;
    label.region = "all";
    label.class_name = name;
    label.annotator = "import";
    label.source = LabelSource::kGroundTruth;
    labels.push_back(std::move(label));
  };
  auto marker_text = [](const XdfMarker& marker) {
    return in_quotes(marker.text) + " at " + shortest_text(marker.time) + " s";
  };
  // The open label: its class, its start, and whether a "start" opened it (index into markers).
  std::string open_class;
  double open_time = 0.0;
  int64_t open_start = -1;  // the "start" marker, -1 for a plain one
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
      add(open_class, open_time, marker.time);
      open = false;
      continue;
    }
    if (kind == -1) throw Error(place, marker_text(marker) + " ends no \"" + name + " start\"");
    if (open) add(open_class, open_time, marker.time);
    open = !name.empty() && xdf_marker_lower(name) != "none";
    open_class = name;
    open_time = marker.time;
    open_start = kind == 1 ? static_cast<int64_t>(k) : -1;
    if (kind == 1 && !open) throw Error(place, marker_text(marker) + " starts no class");
  }
  if (open && open_start >= 0)
    throw Error(where + " marker " + std::to_string(open_start),
                marker_text(markers[static_cast<size_t>(open_start)]) + " is never ended");
  if (open) add(open_class, open_time, end_time);
  return labels;
}

}  // namespace tactile
