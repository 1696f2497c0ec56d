#pragma once
// The generic descriptor set, for any layout (the five skins, grid:RxC, strip:N): per
// channel the Hjorth triple, peak, mean, integral and time of peak; and, when the taxels
// spread over a 2-D map, the contact area over time and the motion of the contact's
// value-weighted centroid.
//
// Parameters: modality = a layout modality, "display" (default: the layout's display
// modality) or "all" (every channel); threshold = contact level as a fraction of the
// segment's value range over the map taxels, in [0, 1) (default 0.2); stream = the stream
// to read (default: the first).

#include <Eigen/Core>
#include <memory>
#include <span>
#include <vector>

#include "tactile/features/feature_extractor.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/stats/statistics.h"

namespace tactile {

struct ChannelSummary {
  stats::Hjorth hjorth;
  double peak = 0.0;       // largest value (channel units)
  double mean = 0.0;       // channel units
  double integral = 0.0;   // sum / rate: channel units x seconds
  int64_t peak_index = 0;  // index of the first largest sample
};
// The per-channel summary of one segment's samples (at least one sample).
ChannelSummary summarise_channel(std::span<const double> values, double rate_hz);

struct ContactMotion {
  double max_area = 0.0;      // map units^2
  double mean_area = 0.0;     // map units^2, over every sample of the segment
  double path_length = 0.0;   // map units, centroid moved sample to sample
  double displacement = 0.0;  // map units, first to last contact centroid
};
// values: samples x taxels; positions and areas: one per taxel. A taxel is in contact at
// a sample when its value passes low + threshold * (high - low), low and high being the
// smallest and largest value over the whole matrix (reversed: below high - threshold *
// (high - low), for modalities where small means close, such as proximity). The centroid
// weighs contact taxels by how far their value is past the segment's rest level (low, or
// high when reversed); samples without contact have no centroid and are left out of the
// path. A matrix with no range has no contact.
ContactMotion contact_motion(const Eigen::MatrixXd& values, const std::vector<Point2>& positions,
                             const Eigen::VectorXd& areas, double threshold, bool reversed);

// True when the points do not all lie on one line (so area and a 2-D path make sense).
bool spans_two_dimensions(const std::vector<Point2>& points);

// Throws tactile::Error naming the parameter on an unknown key or a threshold outside [0, 1).
std::unique_ptr<FeatureExtractor> make_generic_extractor(const Parameters& parameters);

}  // namespace tactile
