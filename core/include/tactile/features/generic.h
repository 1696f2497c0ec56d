#pragma once
// The generic descriptor set, for any layout (the five skins, grid:RxC, strip:N): per
// channel the Hjorth triple, peak, mean, integral and time of peak; and, when the taxels
// spread over a 2-D map, the contact area over time and the motion of the contact's
// value-weighted centroid.
//
// Parameters: modality = a layout modality, "display" (default: the layout's display
// modality) or "all" (every channel); threshold = contact level as a fraction of the
// segment's largest excursion from rest (see contact_motion), in [0, 1) (default 0.2);
// stream = the stream to read (default: the first). The map modality is reversed (small
// values mean touch) when the layout's display_min > display_max. preprocess() finds each
// channel's rest level over the whole recording (quiet_level).

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
  double peak = 0.0;       // largest value (smallest when reversed), channel units
  double mean = 0.0;       // channel units
  double integral = 0.0;   // sum / rate: channel units x seconds
  int64_t peak_index = 0;  // index of the first such sample
};
// The per-channel summary of one segment's samples; reversed for modalities where small
// values mean touch (the layout's display_min > display_max).
ChannelSummary summarise_channel(std::span<const double> values, double rate_hz,
                                 bool reversed = false);

struct ContactMotion {
  double max_area = 0.0;      // map units^2
  double mean_area = 0.0;     // map units^2, over every sample of the segment
  double path_length = 0.0;   // map units, centroid moved sample to sample
  double displacement = 0.0;  // map units, first to last contact centroid
};
// The rest level of a channel over a recording: its 10th percentile (90th when reversed),
// NaN samples ignored; 0 when it has no finite sample.
double quiet_level(std::span<const double> values, bool reversed);

// values: samples x taxels; rest, positions and areas: one per taxel (rest empty: each
// taxel's quietest value in the segment). A taxel's excursion is how far its value is past
// rest in the direction of touch (up, or down when reversed, for modalities where small
// means close, such as proximity or fur counts), 0 on the other side; it is in contact at
// a sample when the excursion exceeds threshold x the largest excursion of any taxel in
// the segment. The centroid weighs contact taxels by their excursion; samples without
// contact have no centroid and are left out of the path. A segment without any excursion
// has no contact.
ContactMotion contact_motion(const Eigen::MatrixXd& values, const Eigen::RowVectorXd& rest,
                             const std::vector<Point2>& positions, const Eigen::VectorXd& areas,
                             double threshold, bool reversed);

// True when the points do not all lie on one line (so area and a 2-D path make sense).
bool spans_two_dimensions(const std::vector<Point2>& points);

// Throws tactile::Error naming the parameter on an unknown key or a threshold outside [0, 1).
std::unique_ptr<FeatureExtractor> make_generic_extractor(const Parameters& parameters);

}  // namespace tactile
