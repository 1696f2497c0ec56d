#include "tactile/features/tsa_event.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <span>

#include "tactile/dsp/tsa_preprocess.h"
#include "tactile/error.h"
#include "tactile/stats/statistics.h"

namespace tactile {

//---- Event geometry (spec §2.5-2.10) ----------------------------------------------------

Point2 tsa_centroid(const TsaFrame& frame) {
  if (frame.empty()) return {};
  // TSA eq. (7): c_n = (1/m_n) Σ_{p in K_n} p.
  Point2 sum;
  for (const TsaContact& contact : frame) {
    sum.x += contact.position.x;
    sum.y += contact.position.y;
  }
  const double count = static_cast<double>(frame.size());
  return {sum.x / count, sum.y / count};
}

double tsa_area(const std::vector<TsaFrame>& frames, TsaAreaMode mode) {
  double area = 0.0;
  for (const TsaFrame& frame : frames) {
    if (mode == TsaAreaMode::kCount) {
      area += static_cast<double>(frame.size());  // Table 3: triggered points
      continue;
    }
    const Point2 centre = tsa_centroid(frame);
    double distances = 0.0;
    double squares = 0.0;
    for (const TsaContact& contact : frame) {
      const double dx = contact.position.x - centre.x;
      const double dy = contact.position.y - centre.y;
      distances += std::hypot(dx, dy);
      squares += dx * dx + dy * dy;
    }
    // TSA eq. (8): text reading Σ ||p - c_n||, or as typeset sqrt(Σ ||p - c_n||²).
    area += mode == TsaAreaMode::kDistanceSum ? distances : std::sqrt(squares);
  }
  return area;
}

std::array<double, 4> tsa_frame_descriptors(const TsaFrame& frame, Point2 sheet_centre) {
  if (frame.empty()) return {0.0, 0.0, 0.0, 0.0};
  std::vector<double> values;
  double farthest = 0.0;
  for (const TsaContact& contact : frame) {
    values.push_back(contact.value);
    farthest = std::max(farthest, std::hypot(contact.position.x - sheet_centre.x,
                                             contact.position.y - sheet_centre.y));
  }
  // TSA §2.5: D1 mean, D2 max, D3 sample std of the active values, D4 max distance from centre.
  return {stats::mean(values), *std::max_element(values.begin(), values.end()),
          stats::sample_std(values), farthest};
}

std::array<double, 8> tsa_descriptor_statistics(const std::vector<TsaFrame>& frames,
                                                Point2 sheet_centre) {
  std::array<std::vector<double>, 4> series;
  for (const TsaFrame& frame : frames) {
    if (frame.empty()) continue;
    const std::array<double, 4> descriptors = tsa_frame_descriptors(frame, sheet_centre);
    for (size_t k = 0; k < 4; ++k) series[k].push_back(descriptors[k]);
  }
  std::array<double, 8> statistics{};
  for (size_t k = 0; k < 4; ++k) {
    // TSA eq. (5): mean over frames; eq. (6): sqrt(Σ (D - mean)² / (N - 1)), N = 1 -> 0.
    statistics[k] = stats::mean(series[k]);
    statistics[4 + k] = stats::sample_std(series[k]);
  }
  return statistics;
}

TsaPathShape tsa_path_shape(const std::vector<Point2>& path) {
  TsaPathShape shape;
  if (path.empty()) return shape;
  const size_t count = path.size();
  for (size_t k = 0; k < count; ++k) {
    const Point2& here = path[k];
    const Point2& next = path[(k + 1) % count];  // closed path: c_{N+1} = c_1
    // Shoelace: S = ½ Σ (x_k y_{k+1} - x_{k+1} y_k); with y down, S > 0 turns clockwise.
    shape.signed_area += 0.5 * (here.x * next.y - next.x * here.y);
    if (k + 1 < count) shape.length += std::hypot(next.x - here.x, next.y - here.y);
  }
  const double dx = path.back().x - path.front().x;
  const double dy = path.back().y - path.front().y;
  shape.net_displacement = std::hypot(dx, dy);
  double angle = std::atan2(-dy, dx) * 180.0 / std::numbers::pi;
  if (angle < 0.0) angle += 360.0;
  shape.angle_degrees = angle >= 360.0 ? 0.0 : angle;
  return shape;
}

int tsa_direction_code(const std::vector<Point2>& path, const TsaDirectionOptions& options) {
  if (path.size() < 2) return 0;
  const TsaPathShape shape = tsa_path_shape(path);
  if (path.size() >= 3 && std::abs(shape.signed_area) >= options.minimum_area &&
      shape.net_displacement < options.rotation_ratio * shape.length)
    return shape.signed_area > 0.0 ? 1 : 2;
  if (shape.net_displacement < options.minimum_displacement) return 0;
  // Eight 45° sectors centred on the axes and diagonals, counter-clockwise from rightwards.
  static constexpr std::array<int, 8> kSectorCodes = {3, 9, 6, 8, 4, 10, 5, 7};
  const auto sector = static_cast<int>(std::floor((shape.angle_degrees + 22.5) / 45.0)) % 8;
  return kSectorCodes[static_cast<size_t>(sector)];
}

//---- The extractor ------------------------------------------------------------------------

namespace {

constexpr std::array<const char*, kTsaDirectionCodes> kDirectionNames = {
    "none",
    "clockwise",
    "counter_clockwise",
    "left_to_right",
    "right_to_left",
    "up_to_down",
    "down_to_up",
    "upper_left_to_lower_right",
    "lower_right_to_upper_left",
    "lower_left_to_upper_right",
    "upper_right_to_lower_left"};

std::string upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

class TsaEventExtractor : public FeatureExtractor {
 public:
  explicit TsaEventExtractor(const Parameters& parameters) {
    std::vector<std::string> known = dsp::tsa_preprocess_keys();
    known.insert(known.end(),
                 {"tsa_features", "area_mode", "direction", "location", "direction_min_area",
                  "direction_ratio", "direction_min_displacement"});
    parameters.expect_only(known);
    preprocess_options_ = dsp::tsa_preprocess_options(parameters);
    const std::string features = upper(parameters.text("tsa_features", "BASIC"));
    if (features != "BASIC" && features != "EXTENDED")
      throw Error(parameters.where(), "tsa_features=" + features + ": expected BASIC or EXTENDED");
    extended_ = features == "EXTENDED";
    const std::string area = upper(parameters.text("area_mode", "TEXT"));
    if (area == "TEXT")
      area_mode_ = TsaAreaMode::kDistanceSum;
    else if (area == "EQ8_LITERAL")
      area_mode_ = TsaAreaMode::kEq8Literal;
    else if (area == "COUNT")
      area_mode_ = TsaAreaMode::kCount;
    else
      throw Error(parameters.where(),
                  "area_mode=" + area + ": expected TEXT, EQ8_LITERAL or COUNT");
    direction_onehot_ = read_encoding(parameters, "direction");
    location_onehot_ = read_encoding(parameters, "location");
    direction_.minimum_area = parameters.number("direction_min_area", direction_.minimum_area);
    direction_.rotation_ratio = parameters.number("direction_ratio", direction_.rotation_ratio);
    direction_.minimum_displacement =
        parameters.number("direction_min_displacement", direction_.minimum_displacement);
  }

  std::string name() const override { return "tsa_event"; }
  std::string description() const override {
    return "Event-triggered capacitive TSA (paper 001): time, direction class (Fig. 8), area (eq. "
           "8) "
           "and sheet location per single-touch event; EXTENDED adds D1-D4 mean and std (eqs. 5-6)";
  }

  std::vector<FeatureColumn> columns(const SkinLayout& layout) const override {
    std::vector<FeatureColumn> columns;
    columns.push_back({"time", "event duration N_ev * T_frame [s] (spec 2.8)"});
    if (direction_onehot_) {
      for (int code = 0; code < kTsaDirectionCodes; ++code) {
        std::string description = "1 when the direction class (spec 2.10, Fig. 8) is code ";
        description.append(std::to_string(code));
        columns.push_back({std::string("direction.") + kDirectionNames[code], description});
      }
    } else {
      columns.push_back(
          {"direction", "direction class 0-10 of the centroid path (spec 2.10, Fig. 8)"});
    }
    const char* area_description = area_mode_ == TsaAreaMode::kDistanceSum
                                       ? "sum over frames of distances of active pads to the "
                                         "frame centroid [pitch] (eq. 8, text reading)"
                                   : area_mode_ == TsaAreaMode::kEq8Literal
                                       ? "sum over frames of the root of summed squared "
                                         "distances to the centroid [pitch] (eq. 8 as typeset)"
                                       : "number of triggered pads summed over frames (Table 3)";
    columns.push_back({"area", area_description});
    if (location_onehot_) {
      for (const Group& group : layout.groups)
        if (group.kind == "sheet")
          columns.push_back({"location." + group.id, "1 when the event is on sheet " + group.id});
    } else {
      columns.push_back({"location", "1-based code of the sheet holding the event (spec 2.9)"});
    }
    if (extended_) {
      static constexpr std::array<const char*, 4> kDescriptors = {
          "mean of active values [counts]", "max of active values [counts]",
          "sample std of active values [counts]",
          "max distance of an active pad from the sheet centre [pitch]"};
      for (const std::string statistic : {"mean", "std"})
        for (size_t k = 0; k < 4; ++k) {
          std::string descriptor = "d";
          descriptor += std::to_string(k + 1);
          std::string description = statistic;
          description.append(statistic == "mean" ? " over frames (eq. 5) of "
                                                 : " over frames (eq. 6, N-1) of ");
          description.append(descriptor).append(", ").append(kDescriptors[k]);
          columns.push_back({descriptor + "_" + statistic, description});
        }
    }
    return columns;
  }

  Recording preprocess(const Recording& recording, const SkinLayout& layout) const override {
    return dsp::tsa_preprocess(recording, layout, preprocess_options_);
  }

  FeatureResult extract(const SegmentInput& input) const override {
    const Stream& stream = dsp::tsa_stream(input.recording);
    const std::vector<dsp::TsaSheet> sheets = dsp::tsa_sheets(input.layout, stream);
    const auto [begin, end] = sample_range(stream, input.segment.t0, input.segment.t1);
    if (begin >= end) return FeatureResult::skip("segment holds no frame");

    // Candidate sheets: those of the segment's region (spec §2.1: the event belongs to the
    // sheet with the most active frames).
    std::vector<const dsp::TsaSheet*> candidates;
    const Group* region =
        input.segment.region == "all" ? nullptr : input.layout.find_group(input.segment.region);
    if (input.segment.region != "all" && region == nullptr)
      return FeatureResult::skip("region " + input.segment.region + " is not a group of layout " +
                                 input.layout.id);
    for (const dsp::TsaSheet& sheet : sheets)
      if (region == nullptr || std::find(region->taxels.begin(), region->taxels.end(),
                                         sheet.taxels.front()) != region->taxels.end())
        candidates.push_back(&sheet);
    if (candidates.empty())
      return FeatureResult::skip("region " + input.segment.region + " holds no sheet");

    const dsp::TsaSheet* best = nullptr;
    int64_t best_frames = 0;
    for (const dsp::TsaSheet* sheet : candidates) {
      int64_t frames = 0;
      for (int64_t n = begin; n < end; ++n) {
        bool active = false;
        for (int column : sheet->columns) {
          const float value = stream.samples(n, column);
          if (std::isnan(value))
            return FeatureResult::skip(
                "missing sample (NaN) at frame " + std::to_string(n) + " of channel " +
                (column < static_cast<int>(stream.channels.size()) ? stream.channels[column]
                                                                   : std::to_string(column)));
          active = active || value > 0.0f;
        }
        frames += active;
      }
      if (frames > best_frames) {
        best_frames = frames;
        best = sheet;
      }
    }
    if (best == nullptr)
      return FeatureResult::skip("no pad triggered on region " + input.segment.region);

    // The event: from the sheet's first to its last active frame inside the segment.
    std::vector<TsaFrame> frames;
    int64_t first = -1;
    int64_t last = -1;
    for (int64_t n = begin; n < end; ++n) {
      TsaFrame frame;
      for (size_t pad = 0; pad < best->columns.size(); ++pad) {
        const float value = stream.samples(n, best->columns[pad]);
        if (value > 0.0f) frame.push_back({best->positions[pad], value});
      }
      if (frame.empty()) continue;
      if (first < 0) first = n;
      last = n;
      frames.push_back(std::move(frame));
    }
    std::vector<Point2> path;
    for (const TsaFrame& frame : frames) path.push_back(tsa_centroid(frame));

    FeatureResult result;
    std::vector<double>& values = result.values;
    values.push_back(static_cast<double>(last - first + 1) / stream.rate_hz);  // spec §2.8
    const int direction = tsa_direction_code(path, direction_);
    if (direction_onehot_) {
      for (int code = 0; code < kTsaDirectionCodes; ++code)
        values.push_back(code == direction ? 1.0 : 0.0);
    } else {
      values.push_back(direction);
    }
    values.push_back(tsa_area(frames, area_mode_));
    if (location_onehot_) {
      for (const dsp::TsaSheet& sheet : sheets) values.push_back(&sheet == best ? 1.0 : 0.0);
    } else {
      values.push_back(best->code);
    }
    if (extended_) {
      const std::array<double, 8> statistics = tsa_descriptor_statistics(frames, best->centre);
      values.insert(values.end(), statistics.begin(), statistics.end());
    }
    return result;
  }

 private:
  static bool read_encoding(const Parameters& parameters, const std::string& key) {
    const std::string encoding = parameters.text(key, "code");
    if (encoding != "code" && encoding != "onehot")
      throw Error(parameters.where(), key + "=" + encoding + ": expected code or onehot");
    return encoding == "onehot";
  }

  dsp::TsaPreprocessOptions preprocess_options_;
  bool extended_ = false;
  TsaAreaMode area_mode_ = TsaAreaMode::kDistanceSum;
  bool direction_onehot_ = false;
  bool location_onehot_ = false;
  TsaDirectionOptions direction_;
};

}  // namespace

std::unique_ptr<FeatureExtractor> make_tsa_event_extractor(const Parameters& parameters) {
  return std::make_unique<TsaEventExtractor>(parameters);
}

}  // namespace tactile
