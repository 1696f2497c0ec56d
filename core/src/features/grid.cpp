// The whole-grid descriptor set (grid.h): per-frame figures of the pressed region, summarised
// over the segment.
#include "tactile/features/grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>

#include "tactile/error.h"
#include "tactile/features/generic.h"
#include "tactile/stats/statistics.h"

namespace tactile {

namespace {

// The stream preprocess() adds: row 0 each channel's rest level, row 1 its noise deviation.
constexpr const char* kGridRestStream = "grid.rest";
// A normal distribution's standard deviation in median absolute deviations.
constexpr double kMadToDeviation = 1.4826;
// Neighbours: taxels within this multiple of a taxel's nearest distance (4-connected on a grid).
constexpr double kNeighbourReach = 1.2;
// A centroid step shorter than this share of the pitch has no direction (noise).
constexpr double kStillStep = 0.1;

// Mean, max and (population) standard deviation of the values where `keep` holds; zeros
// when none does.
void add_moments(const Eigen::VectorXd& values, const std::vector<bool>& keep,
                 std::vector<double>& out) {
  double sum = 0.0, squares = 0.0, largest = 0.0;
  int64_t count = 0;
  for (Eigen::Index k = 0; k < values.size(); ++k) {
    if (!keep[static_cast<size_t>(k)]) continue;
    const double value = values(k);
    largest = count == 0 ? value : std::max(largest, value);
    sum += value;
    squares += value * value;
    ++count;
  }
  if (count == 0) {
    out.insert(out.end(), {0.0, 0.0, 0.0});
    return;
  }
  const double mean = sum / static_cast<double>(count);
  out.insert(out.end(),
             {mean, largest,
              std::sqrt(std::max(0.0, squares / static_cast<double>(count) - mean * mean))});
}

void add_moment_columns(const std::string& name, const std::string& what, const std::string& unit,
                        std::vector<FeatureColumn>& columns) {
  columns.push_back({name + "_mean", "mean of " + what + ", " + unit});
  columns.push_back({name + "_max", "largest " + what + ", " + unit});
  columns.push_back({name + "_std", "standard deviation of " + what + ", " + unit});
}

}  // namespace

//---- The map and its rest

GridMap grid_map(const SkinLayout& layout, const std::string& modality, const std::string& where) {
  const int slot = layout.modality_index(modality);
  if (slot < 0) {
    std::string known;
    for (const std::string& name : layout.modalities) known += (known.empty() ? "" : ", ") + name;
    throw Error(where, "modality=" + modality + ": layout " + layout.id +
                           " has no such modality (has: " + known + ")");
  }
  GridMap map;
  std::vector<Point2> positions;
  std::vector<double> x, y, areas;
  for (const Taxel& taxel : layout.taxels) {
    if (static_cast<size_t>(slot) >= taxel.channels.size()) continue;
    const int channel = taxel.channels[static_cast<size_t>(slot)];
    if (channel < 0) continue;
    map.channels.push_back(channel);
    map.taxels.push_back(taxel.id);
    positions.push_back(taxel.position);
    x.push_back(taxel.position.x);
    y.push_back(taxel.position.y);
    areas.push_back(taxel.area > 0.0 ? taxel.area : taxel.size.x * taxel.size.y);
  }
  const auto count = static_cast<Eigen::Index>(x.size());
  map.x = Eigen::Map<const Eigen::VectorXd>(x.data(), count);
  map.y = Eigen::Map<const Eigen::VectorXd>(y.data(), count);
  map.areas = Eigen::Map<const Eigen::VectorXd>(areas.data(), count);
  map.pitch = count > 0 && map.areas.mean() > 0.0 ? std::sqrt(map.areas.mean()) : 1.0;
  map.two_dimensional = spans_two_dimensions(positions);
  map.reversed = layout.display_min > layout.display_max && modality == layout.display_modality;
  // Neighbours by distance; each taxel's nearest other decides its reach.
  map.neighbours.resize(static_cast<size_t>(count));
  std::vector<double> nearest(static_cast<size_t>(count), std::numeric_limits<double>::infinity());
  for (Eigen::Index a = 0; a < count; ++a)
    for (Eigen::Index b = 0; b < count; ++b) {
      const double distance = std::hypot(map.x(a) - map.x(b), map.y(a) - map.y(b));
      if (a != b && distance > 1e-12)
        nearest[static_cast<size_t>(a)] = std::min(nearest[static_cast<size_t>(a)], distance);
    }
  for (Eigen::Index a = 0; a < count; ++a)
    for (Eigen::Index b = 0; b < count; ++b) {
      const double distance = std::hypot(map.x(a) - map.x(b), map.y(a) - map.y(b));
      if (a != b && distance <= kNeighbourReach * nearest[static_cast<size_t>(a)])
        map.neighbours[static_cast<size_t>(a)].push_back(static_cast<int>(b));
    }
  return map;
}

GridMap grid_submap(const GridMap& map, const std::vector<size_t>& members) {
  GridMap part;
  const auto count = static_cast<Eigen::Index>(members.size());
  part.x.resize(count);
  part.y.resize(count);
  part.areas.resize(count);
  std::vector<int> index_of(map.channels.size(), -1);
  for (size_t k = 0; k < members.size(); ++k) index_of[members[k]] = static_cast<int>(k);
  for (size_t k = 0; k < members.size(); ++k) {
    const size_t member = members[k];
    const auto at = static_cast<Eigen::Index>(k);
    part.channels.push_back(map.channels[member]);
    part.taxels.push_back(map.taxels[member]);
    part.x(at) = map.x(static_cast<Eigen::Index>(member));
    part.y(at) = map.y(static_cast<Eigen::Index>(member));
    part.areas(at) = map.areas(static_cast<Eigen::Index>(member));
    std::vector<int> neighbours;
    for (int other : map.neighbours[member])
      if (index_of[static_cast<size_t>(other)] >= 0)
        neighbours.push_back(index_of[static_cast<size_t>(other)]);
    part.neighbours.push_back(std::move(neighbours));
  }
  part.pitch = map.pitch;
  part.reversed = map.reversed;
  part.two_dimensional = map.two_dimensional;
  return part;
}

GridRest grid_rest(const Eigen::MatrixXd& values, bool reversed) {
  (void)reversed;  // the median and its deviation are the same either way
  GridRest rest;
  const Eigen::Index taxels = values.cols();
  rest.rest = Eigen::RowVectorXd::Zero(taxels);
  rest.noise = Eigen::RowVectorXd::Zero(taxels);
  std::vector<double> positive;
  for (Eigen::Index taxel = 0; taxel < taxels; ++taxel) {
    std::vector<double> finite;
    for (Eigen::Index frame = 0; frame < values.rows(); ++frame)
      if (std::isfinite(values(frame, taxel))) finite.push_back(values(frame, taxel));
    if (finite.empty()) continue;
    const double median = stats::median(finite);
    for (double& value : finite) value = std::abs(value - median);
    rest.rest(taxel) = median;
    rest.noise(taxel) = kMadToDeviation * stats::median(finite);
    if (rest.noise(taxel) > 0.0) positive.push_back(rest.noise(taxel));
  }
  // Quantised or stuck taxels have a deviation of 0: the typical taxel's noise is their floor.
  const double floor = positive.empty() ? 1e-9 : 0.5 * stats::median(positive);
  rest.noise = rest.noise.cwiseMax(floor);
  return rest;
}

//---- Per frame

GridFrames grid_frames(const Eigen::MatrixXd& values, const GridRest& rest, const GridMap& map,
                       double threshold, double peak_share) {
  const Eigen::Index frames = values.rows(), taxels = values.cols();
  GridFrames out;
  for (Eigen::VectorXd* series :
       {&out.total, &out.area, &out.peak, &out.intensity, &out.spread, &out.major, &out.minor,
        &out.eccentricity, &out.orientation, &out.blobs})
    *series = Eigen::VectorXd::Zero(frames);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.centroid_x = Eigen::VectorXd::Constant(frames, nan);
  out.centroid_y = Eigen::VectorXd::Constant(frames, nan);
  out.contact.assign(static_cast<size_t>(frames), false);
  const Eigen::ArrayXXd past_rest = (map.reversed ? Eigen::ArrayXXd((-values).rowwise() + rest.rest)
                                                  : Eigen::ArrayXXd(values.rowwise() - rest.rest))
                                        .cwiseMax(0.0);
  const double largest = past_rest.size() > 0 ? past_rest.maxCoeff() : 0.0;
  const Eigen::ArrayXXd level =
      (threshold * rest.noise).replicate(frames, 1).array().max(peak_share * largest);
  const Eigen::ArrayXXd weights = (past_rest > level).select(past_rest, 0.0);
  std::vector<int> label(static_cast<size_t>(taxels));
  std::vector<int> stack;
  for (Eigen::Index frame = 0; frame < frames; ++frame) {
    const Eigen::ArrayXd w = weights.row(frame).transpose();
    const double total = w.sum();
    if (!(total > 0.0)) continue;
    out.contact[static_cast<size_t>(frame)] = true;
    const Eigen::ArrayXd in_contact = (w > 0.0).cast<double>();
    const double count = in_contact.sum();
    out.total(frame) = total;
    out.area(frame) = (in_contact * map.areas.array()).sum();
    out.peak(frame) = w.maxCoeff();
    out.intensity(frame) = total / count;
    const double cx = (w * map.x.array()).sum() / total, cy = (w * map.y.array()).sum() / total;
    out.centroid_x(frame) = cx;
    out.centroid_y(frame) = cy;
    const Eigen::ArrayXd dx = map.x.array() - cx, dy = map.y.array() - cy;
    const double xx = (w * dx * dx).sum() / total, yy = (w * dy * dy).sum() / total,
                 xy = (w * dx * dy).sum() / total;
    // Eigenvalues of the 2 x 2 covariance [[xx, xy], [xy, yy]].
    const double half_trace = 0.5 * (xx + yy);
    const double root = std::sqrt(std::max(0.0, 0.25 * (xx - yy) * (xx - yy) + xy * xy));
    const double large = half_trace + root, small = std::max(0.0, half_trace - root);
    out.spread(frame) = std::sqrt(std::max(0.0, xx + yy));
    out.major(frame) = std::sqrt(large);
    out.minor(frame) = std::sqrt(small);
    out.eccentricity(frame) = large > 0.0 ? std::sqrt(std::max(0.0, 1.0 - small / large)) : 0.0;
    double angle = 0.5 * std::atan2(2.0 * xy, xx - yy);
    if (angle < 0.0) angle += std::numbers::pi;
    out.orientation(frame) = angle;
    // Connected groups of contact taxels (flood fill over the neighbours).
    std::fill(label.begin(), label.end(), 0);
    int blobs = 0;
    for (Eigen::Index seed = 0; seed < taxels; ++seed) {
      if (!(w(seed) > 0.0) || label[static_cast<size_t>(seed)] != 0) continue;
      ++blobs;
      label[static_cast<size_t>(seed)] = blobs;
      stack.assign(1, static_cast<int>(seed));
      while (!stack.empty()) {
        const int at = stack.back();
        stack.pop_back();
        for (int next : map.neighbours[static_cast<size_t>(at)])
          if (w(next) > 0.0 && label[static_cast<size_t>(next)] == 0) {
            label[static_cast<size_t>(next)] = blobs;
            stack.push_back(next);
          }
      }
    }
    out.blobs(frame) = blobs;
  }
  return out;
}

//---- The segment's summary

std::vector<FeatureColumn> grid_columns(const std::string& prefix, const std::string& unit,
                                        const std::string& map_unit) {
  const std::string p = prefix;
  const std::string frames = " over the frames with contact";
  std::vector<FeatureColumn> columns;
  columns.push_back({p + "duration", "segment length, s"});
  columns.push_back({p + "contact_share", "share of the segment's frames with a contact taxel"});
  const std::string total = "the total excursion (sum over contact taxels of the value past rest)";
  add_moment_columns(p + "total", total + " over the segment's frames", unit, columns);
  columns.push_back({p + "total_integral", "sum of " + total + " / sample rate, " + unit + " x s"});
  columns.push_back(
      {p + "total_peak_time", "time of the largest total excursion after the segment's start, s"});
  columns.push_back({p + "total_peak_position", "that time as a share of the segment's length"});
  columns.push_back(
      {p + "total_rise", "time from the first contact frame to the largest total excursion, s"});
  columns.push_back(
      {p + "total_fall", "time from the largest total excursion to the last contact frame, s"});
  columns.push_back(
      {p + "total_onsets", "rises of the total excursion through half its largest, per s"});
  columns.push_back(
      {p + "total_roughness",
       "sum of |frame-to-frame change| of the total excursion over twice its largest, per s"});
  add_moment_columns(p + "area", "the contact area over the segment's frames", map_unit + "^2",
                     columns);
  add_moment_columns(p + "peak", "the largest excursion of a taxel over the segment's frames", unit,
                     columns);
  add_moment_columns(p + "intensity", "the mean excursion of the contact taxels" + frames, unit,
                     columns);
  add_moment_columns(
      p + "spread",
      "sqrt of the trace of the excursion-weighted covariance of the contact taxels' positions" +
          frames,
      map_unit, columns);
  add_moment_columns(
      p + "major", "the pressed region's major semi-axis (sqrt of the larger eigenvalue)" + frames,
      map_unit, columns);
  add_moment_columns(
      p + "minor", "the pressed region's minor semi-axis (sqrt of the smaller eigenvalue)" + frames,
      map_unit, columns);
  add_moment_columns(p + "eccentricity",
                     "the pressed region's eccentricity sqrt(1 - minor^2/major^2)" + frames,
                     "0 round .. 1 a line", columns);
  add_moment_columns(p + "blobs", "the connected groups of contact taxels" + frames, "count",
                     columns);
  add_moment_columns(p + "speed", "the contact centroid's speed between consecutive contact frames",
                     map_unit + "/s", columns);
  columns.push_back(
      {p + "path_length",
       "distance the excursion-weighted centroid moves, frame to frame, " + map_unit});
  columns.push_back(
      {p + "displacement", "distance from the first to the last contact centroid, " + map_unit});
  columns.push_back(
      {p + "straightness", "displacement / path length (1: a straight path; 0 without motion)"});
  columns.push_back(
      {p + "alignment",
       "speed-weighted mean |cos| of the angle between the centroid's motion and the major axis "
       "(1: moving lengthwise, as a stroke)"});
  columns.push_back(
      {p + "reversals",
       "turns of the centroid's motion by more than 90 degrees between steps of at least 0.1 "
       "pitch, per s"});
  columns.push_back({p + "orientation_mean",
                     "mean orientation of the major axis from +x, weighted by major^2 - minor^2, "
                     "radians in [0, pi)"});
  columns.push_back(
      {p + "orientation_spread",
       "1 - length of the weighted mean of the doubled orientation angle (0: steady axis)"});
  return columns;
}

std::vector<double> grid_summary(const GridFrames& frames, const GridMap& map, double rate_hz) {
  const auto n = static_cast<int64_t>(frames.total.size());
  std::vector<double> out;
  out.reserve(kGridColumnCount);
  const std::vector<bool> every(static_cast<size_t>(n), true);
  const std::vector<bool>& contact = frames.contact;
  const int64_t with_contact = std::count(contact.begin(), contact.end(), true);
  out.push_back(static_cast<double>(n) / rate_hz);
  out.push_back(n > 0 ? static_cast<double>(with_contact) / static_cast<double>(n) : 0.0);

  // The total excursion over time.
  add_moments(frames.total, every, out);
  const double largest = n > 0 ? frames.total.maxCoeff() : 0.0;
  Eigen::Index peak_frame = 0;
  if (n > 0) frames.total.maxCoeff(&peak_frame);
  int64_t first_contact = -1, last_contact = -1;
  for (int64_t k = 0; k < n; ++k)
    if (contact[static_cast<size_t>(k)]) {
      if (first_contact < 0) first_contact = k;
      last_contact = k;
    }
  const double seconds = std::max(1.0, static_cast<double>(n)) / rate_hz;
  out.push_back(frames.total.sum() / rate_hz);
  out.push_back(static_cast<double>(peak_frame) / rate_hz);
  out.push_back(n > 1 ? static_cast<double>(peak_frame) / static_cast<double>(n - 1) : 0.0);
  out.push_back(first_contact >= 0 ? static_cast<double>(peak_frame - first_contact) / rate_hz
                                   : 0.0);
  out.push_back(last_contact >= 0 ? static_cast<double>(last_contact - peak_frame) / rate_hz : 0.0);
  int64_t onsets = 0;
  double change = 0.0;
  bool above = false;
  for (int64_t k = 0; k < n; ++k) {
    const bool now = largest > 0.0 && frames.total(k) > 0.5 * largest;
    if (now && !above) ++onsets;
    above = now;
    if (k > 0) change += std::abs(frames.total(k) - frames.total(k - 1));
  }
  out.push_back(static_cast<double>(onsets) / seconds);
  out.push_back(largest > 0.0 ? change / (2.0 * largest) / seconds : 0.0);

  add_moments(frames.area, every, out);
  add_moments(frames.peak, every, out);
  for (const Eigen::VectorXd* series : {&frames.intensity, &frames.spread, &frames.major,
                                        &frames.minor, &frames.eccentricity, &frames.blobs})
    add_moments(*series, contact, out);

  // The centroid's motion between consecutive contact frames.
  Eigen::VectorXd speed = Eigen::VectorXd::Zero(n);
  std::vector<bool> moving(static_cast<size_t>(n), false);
  double path = 0.0, aligned = 0.0;
  int64_t reversals = 0;
  double last_dx = 0.0, last_dy = 0.0;
  bool has_last = false;
  for (int64_t k = 1; k < n; ++k) {
    if (!contact[static_cast<size_t>(k)] || !contact[static_cast<size_t>(k - 1)]) continue;
    const double dx = frames.centroid_x(k) - frames.centroid_x(k - 1);
    const double dy = frames.centroid_y(k) - frames.centroid_y(k - 1);
    const double step = std::hypot(dx, dy);
    speed(k) = step * rate_hz;
    moving[static_cast<size_t>(k)] = true;
    path += step;
    const double axis = frames.orientation(k);
    if (step > 0.0) aligned += std::abs(dx * std::cos(axis) + dy * std::sin(axis));
    if (step >= kStillStep * map.pitch) {
      if (has_last && dx * last_dx + dy * last_dy < 0.0) ++reversals;
      last_dx = dx, last_dy = dy, has_last = true;
    }
  }
  add_moments(speed, moving, out);
  out.push_back(path);
  double displacement = 0.0;
  if (first_contact >= 0)
    displacement = std::hypot(frames.centroid_x(last_contact) - frames.centroid_x(first_contact),
                              frames.centroid_y(last_contact) - frames.centroid_y(first_contact));
  out.push_back(displacement);
  out.push_back(path > 0.0 ? std::min(1.0, displacement / path) : 0.0);
  out.push_back(path > 0.0 ? aligned / path : 0.0);
  out.push_back(static_cast<double>(reversals) / seconds);

  // Orientation as a doubled angle (an axis, not a direction), weighted by how elongated.
  double sum_cos = 0.0, sum_sin = 0.0, weight = 0.0;
  for (int64_t k = 0; k < n; ++k) {
    if (!contact[static_cast<size_t>(k)]) continue;
    const double w = frames.major(k) * frames.major(k) - frames.minor(k) * frames.minor(k);
    sum_cos += w * std::cos(2.0 * frames.orientation(k));
    sum_sin += w * std::sin(2.0 * frames.orientation(k));
    weight += w;
  }
  double mean_angle = 0.0, angle_spread = 0.0;
  if (weight > 0.0) {
    mean_angle = 0.5 * std::atan2(sum_sin, sum_cos);
    if (mean_angle < 0.0) mean_angle += std::numbers::pi;
    angle_spread = std::max(0.0, 1.0 - std::hypot(sum_cos, sum_sin) / weight);
  }
  out.push_back(mean_angle);
  out.push_back(angle_spread);
  return out;
}

//---- Whole recordings and segments

void add_grid_rest(Recording& recording, const Stream& stream, const GridMap& map) {
  Eigen::MatrixXd values(stream.sample_count(), static_cast<Eigen::Index>(map.channels.size()));
  for (size_t k = 0; k < map.channels.size(); ++k)
    values.col(static_cast<Eigen::Index>(k)) = stream.samples.col(map.channels[k]).cast<double>();
  const GridRest rest = grid_rest(values, map.reversed);
  Stream levels;
  levels.name = kGridRestStream;
  levels.rate_hz = stream.rate_hz;
  levels.channels = stream.channels;
  levels.units = stream.units;
  levels.samples = SampleMatrix::Zero(2, stream.channel_count());
  for (size_t k = 0; k < map.channels.size(); ++k) {
    levels.samples(0, map.channels[k]) =
        static_cast<float>(rest.rest(static_cast<Eigen::Index>(k)));
    levels.samples(1, map.channels[k]) =
        static_cast<float>(rest.noise(static_cast<Eigen::Index>(k)));
  }
  recording.streams.push_back(std::move(levels));
}

GridMap grid_region(const GridMap& map, const SkinLayout& layout, const std::string& region,
                    std::string& skip_reason) {
  if (region == "all" || region.empty()) return map;
  const Group* group = layout.find_group(region);
  if (group == nullptr) {
    skip_reason = "region '" + region + "' is not a group of layout " + layout.id;
    return {};
  }
  const std::set<int64_t> in_group(group->taxels.begin(), group->taxels.end());
  std::vector<size_t> members;
  for (size_t k = 0; k < map.taxels.size(); ++k)
    if (in_group.count(map.taxels[k])) members.push_back(k);
  return grid_submap(map, members);
}

std::vector<double> grid_segment(const Recording& recording, const Stream& stream,
                                 const GridMap& map, int64_t first, int64_t count, double threshold,
                                 std::string& skip_reason, double peak_share) {
  Eigen::MatrixXd values(count, static_cast<Eigen::Index>(map.channels.size()));
  for (size_t k = 0; k < map.channels.size(); ++k)
    values.col(static_cast<Eigen::Index>(k)) =
        stream.samples.col(map.channels[k]).segment(first, count).cast<double>();
  if (!values.allFinite()) {
    skip_reason = "NaN or infinite sample in the segment";
    return {};
  }
  GridRest rest;
  if (const Stream* levels = recording.find_stream(kGridRestStream)) {
    rest.rest.resize(values.cols());
    rest.noise.resize(values.cols());
    for (size_t k = 0; k < map.channels.size(); ++k) {
      rest.rest(static_cast<Eigen::Index>(k)) = levels->samples(0, map.channels[k]);
      rest.noise(static_cast<Eigen::Index>(k)) = levels->samples(1, map.channels[k]);
    }
  } else {
    rest = grid_rest(values, map.reversed);
  }
  return grid_summary(grid_frames(values, rest, map, threshold, peak_share), map, stream.rate_hz);
}

//---- The extractor

namespace {

class GridExtractor : public FeatureExtractor {
 public:
  GridExtractor(std::string modality, double threshold, double peak_share, std::string stream,
                std::string where)
      : modality_(std::move(modality)),
        threshold_(threshold),
        peak_share_(peak_share),
        stream_(std::move(stream)),
        where_(std::move(where)) {}

  std::string name() const override { return "grid"; }
  std::string description() const override {
    return "2-D skins of any size: per frame the pressed region's total excursion past rest "
           "(median), "
           "area (taxels past " +
           std::to_string(static_cast<int>(threshold_)) +
           " noise deviations), peak, centroid speed, spread, principal axes, eccentricity, "
           "orientation and blobs; summarised over the touch (mean, max, std, timing, path): "
           "the same columns for every grid size, wherever the touch lands";
  }

  std::vector<FeatureColumn> columns(const SkinLayout& layout) const override {
    const GridMap map = map_for(layout);
    const std::string unit = unit_of(layout, map);
    return grid_columns("grid.", unit, layout.map_unit.empty() ? "map units" : layout.map_unit);
  }

  Recording preprocess(const Recording& recording, const SkinLayout& layout) const override {
    Recording prepared = with_layout_stream(recording, layout, stream_);
    prepared.streams.reserve(prepared.streams.size() + 1);  // the stream stays valid below
    add_grid_rest(prepared, find_stream(prepared, layout), map_for(layout));
    return prepared;
  }

  FeatureResult extract(const SegmentInput& input) const override {
    const Stream& stream = find_stream(input.recording, input.layout);
    std::string skip_reason;
    const GridMap map =
        grid_region(map_for(input.layout), input.layout, input.segment.region, skip_reason);
    if (!skip_reason.empty()) return FeatureResult::skip(skip_reason);
    const auto [first, last] = sample_range(stream, input.segment.t0, input.segment.t1);
    if (last <= first) return FeatureResult::skip("segment holds no samples");
    FeatureResult result;
    result.values = grid_segment(input.recording, stream, map, first, last - first, threshold_,
                                 skip_reason, peak_share_);
    if (!skip_reason.empty()) return FeatureResult::skip(skip_reason);
    return result;
  }

 private:
  std::string modality_of(const SkinLayout& layout) const {
    if (modality_ != "display") return modality_;
    return layout.display_modality.empty() && !layout.modalities.empty() ? layout.modalities.front()
                                                                         : layout.display_modality;
  }

  GridMap map_for(const SkinLayout& layout) const {
    GridMap map = grid_map(layout, modality_of(layout), where_);
    if (!map.two_dimensional)
      throw Error(where_, "layout " + layout.id +
                              ": its taxels do not spread over a 2-D map (use generic)");
    return map;
  }

  static std::string unit_of(const SkinLayout& layout, const GridMap& map) {
    if (map.channels.empty()) return "units";
    const std::string& unit = layout.channels[static_cast<size_t>(map.channels.front())].unit;
    return unit.empty() ? "units" : unit;
  }

  const Stream& find_stream(const Recording& recording, const SkinLayout& layout) const {
    return ordered_stream(recording, layout, stream_, "speeds need");
  }

  std::string modality_;
  double threshold_;
  double peak_share_;
  std::string stream_;
  std::string where_;
};

}  // namespace

std::unique_ptr<FeatureExtractor> make_grid_extractor(const Parameters& parameters) {
  parameters.expect_only({"modality", "threshold", "share", "stream"});
  const double threshold = parameters.number("threshold", kGridDefaultThreshold);
  if (!(threshold > 0.0))
    throw Error(parameters.where(),
                "threshold=" + parameters.text("threshold", "") + ": must be positive");
  const double share = parameters.number("share", kGridDefaultPeakShare);
  if (!(share >= 0.0 && share < 1.0))
    throw Error(parameters.where(),
                "share=" + parameters.text("share", "") + ": must be in [0, 1)");
  return std::make_unique<GridExtractor>(parameters.text("modality", "display"), threshold, share,
                                         parameters.text("stream", ""), parameters.where());
}

}  // namespace tactile
