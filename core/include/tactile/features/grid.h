#pragma once
// The whole-grid descriptor set (`grid` pipeline), for skins whose taxels spread over a 2-D
// map: per frame the pressed region's total excursion, area, peak, centroid and its
// velocity, spread, principal axes, orientation, eccentricity and number of blobs;
// summarised over the segment in a fixed set of columns, whatever the grid's size and
// wherever on it the touch lands (no absolute position: only motion and shape).
//
// Parameters: modality = a layout modality or "display" (default); threshold = contact
// level in noise deviations past rest (default 4); share = a taxel is in contact only where it
// is also past this share of the segment's largest excursion (default 0: every taxel past the
// noise; 0.5, the route for people's touches on a grid (docs/FEATURES.md): the region where the
// touch presses at least half as hard as its hardest point, as a full width at half maximum
// measures a peak); stream = the stream to read (default: the first). preprocess() finds each
// taxel's rest level (median over the recording) and noise (1.4826 x its median absolute deviation,
// floored at half the median of the taxels' noises, so a stuck or quantised taxel does not count
// every count as contact). Small values mean touch when the layout's display_min > display_max.
//
// The generic pipeline uses the same per-frame code for layouts of many taxels
// (kGridTaxelsForGeneric, generic.h).

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "tactile/features/feature_extractor.h"
#include "tactile/layout/skin_layout.h"

namespace tactile {

// The taxels of one modality on the map, with what the per-frame figures need.
struct GridMap {
  std::vector<int> channels;  // recording column of each map taxel
  std::vector<int64_t> taxels;
  Eigen::VectorXd x, y, areas;               // map units, map units^2
  std::vector<std::vector<int>> neighbours;  // map taxels within 1.2 x the nearest distance
  double pitch = 1.0;                        // sqrt of the mean taxel area
  bool reversed = false;                     // small values mean touch
  bool two_dimensional = false;              // the taxels do not all lie on one line
};
// Throws tactile::Error at `where` when the layout has no such modality.
GridMap grid_map(const SkinLayout& layout, const std::string& modality, const std::string& where);
// The same map restricted to some of its taxels (indices into map), e.g. one group's.
GridMap grid_submap(const GridMap& map, const std::vector<size_t>& members);

// Each map taxel's rest level and noise deviation over a whole stream (see above).
struct GridRest {
  Eigen::RowVectorXd rest, noise;
};
GridRest grid_rest(const Eigen::MatrixXd& values, bool reversed);

// The per-frame figures of a segment; values: frames x map taxels.
struct GridFrames {
  Eigen::VectorXd total;         // sum of the contact taxels' excursions past rest
  Eigen::VectorXd area;          // contact taxels' area, map units^2
  Eigen::VectorXd peak;          // largest excursion of a contact taxel
  Eigen::VectorXd intensity;     // total / contact taxels
  Eigen::VectorXd spread;        // sqrt of the trace of the weighted covariance, map units
  Eigen::VectorXd major, minor;  // sqrt of its eigenvalues, map units
  Eigen::VectorXd eccentricity;  // sqrt(1 - minor^2 / major^2), 0 round .. 1 a line
  Eigen::VectorXd orientation;   // of the major axis from +x, radians in [0, pi)
  Eigen::VectorXd blobs;         // connected groups of contact taxels
  Eigen::VectorXd centroid_x, centroid_y;  // excursion-weighted, map units; NaN without contact
  std::vector<bool> contact;               // any contact taxel in the frame
};
// A taxel is in contact when its excursion exceeds threshold x its noise deviation and
// peak_share x the largest excursion of any taxel in the segment.
GridFrames grid_frames(const Eigen::MatrixXd& values, const GridRest& rest, const GridMap& map,
                       double threshold, double peak_share = 0.0);

// The columns of grid_summary, each name prefixed by `prefix` ("grid." in the grid pipeline),
// `unit` the values' unit and `map_unit` the map's.
std::vector<FeatureColumn> grid_columns(const std::string& prefix, const std::string& unit,
                                        const std::string& map_unit);
// The segment's summary of its frames, in grid_columns order.
std::vector<double> grid_summary(const GridFrames& frames, const GridMap& map, double rate_hz);
inline constexpr size_t kGridColumnCount = 46;
inline constexpr double kGridDefaultThreshold = 4.0;
inline constexpr double kGridDefaultPeakShare = 0.0;

// What preprocess() does: adds a stream "grid.rest" to `recording` holding, per channel of
// `stream`, its rest level (row 0) and noise deviation (row 1); map taxels only, 0 elsewhere.
void add_grid_rest(Recording& recording, const Stream& stream, const GridMap& map);
// The map's taxels in the segment's region ("all" or a layout group); empty with a reason in
// `skip_reason` for a region that is no group.
GridMap grid_region(const GridMap& map, const SkinLayout& layout, const std::string& region,
                    std::string& skip_reason);
// grid_summary of samples [first, first + count) of `stream` over the map's taxels, with the
// rest levels of the recording's "grid.rest" stream (without one: the segment's own).
// Empty with a reason in `skip_reason` when a value is not finite.
std::vector<double> grid_segment(const Recording& recording, const Stream& stream,
                                 const GridMap& map, int64_t first, int64_t count, double threshold,
                                 std::string& skip_reason, double peak_share = 0.0);

// Throws tactile::Error naming the parameter on an unknown key, a threshold that is not
// positive or a share outside [0, 1).
std::unique_ptr<FeatureExtractor> make_grid_extractor(const Parameters& parameters);

}  // namespace tactile
