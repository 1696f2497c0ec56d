#pragma once
// The generic descriptor set, for any layout (the five skins, grid:RxC, strip:N): per
// channel the Hjorth triple, peak, mean, integral and time of peak; and, when the taxels
// spread over a 2-D map, the contact area over time and the motion of the contact's
// value-weighted centroid.
//
// Parameters: modality = a layout modality, "display" (default: the layout's display
// modality) or "all" (every channel); threshold = contact level as a fraction of the
// segment's largest excursion from rest (see contact_motion), in [0, 1) (default 0.2);
// stream = the stream to read (default: the first); per_channel = auto (default), yes or no:
// the per-channel block (26 columns per channel, the busiest channel's again and the
// neighbours' correlation) for layouts of at most kGridTaxelsForGeneric channels, or where
// the taxels do not spread over 2-D; for larger 2-D layouts, instead of the per-channel
// block, the whole-grid columns of the grid pipeline (grid.h) prefixed "grid." (layout_note
// says which). The map modality is reversed (small
// values mean touch) when the layout's display_min > display_max. preprocess() finds each
// channel's rest level over the whole recording (quiet_level).

#include <Eigen/Core>
#include <memory>
#include <span>
#include <vector>

#include "tactile/features/feature_extractor.h"
#include "tactile/features/grid.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/stats/statistics.h"

namespace tactile {

// Above this many channels on a 2-D map, generic's per_channel=auto leaves the per-channel
// block out and writes whole-grid columns: a tree or SVM on thousands of per-taxel columns
// learns where touches landed, not what they were. The papers' nao (32 force cells) and flux
// (8) stay per channel; fur (160), robovie (274) and tsa (672) get whole-grid columns.
inline constexpr size_t kGridTaxelsForGeneric = 64;

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
  double spread = 0.0;        // map units: excursion-weighted distance of contact from the
                              // centroid, mean over the samples with contact
};

// How a channel's signal runs over a segment, in ways that compare across segments of
// different lengths and skins with no paper of their own (issue "Other people's data").
inline constexpr int kEnvelopeBins = 8;
struct ChannelShape {
  double median = 0.0, q10 = 0.0, q90 = 0.0;  // robust level and spread, channel units
  // Shares of the mean-removed signal's energy below fs/16, in [fs/16, fs/8), and from fs/8
  // up (0 for a constant segment).
  double band_low = 0.0, band_mid = 0.0, band_high = 0.0;
  double zero_crossings = 0.0;  // of the mean-removed signal, per second
  double peaks = 0.0;           // rises of the excursion through half its largest, per second
  double onset_slope = 0.0;     // steepest rise of the excursion in the first half, units/s
  double release_slope = 0.0;   // steepest fall of the excursion in the second half, units/s
  double active_seconds = 0.0;  // time the excursion exceeds 3 noise deviations
  double envelope[kEnvelopeBins] = {};  // mean excursion in 8 equal parts of the segment
};
// `rest`: the channel's rest level (NaN: the segment's own quietest decile); the excursion
// is |x - rest| (toward touch for reversed modalities: rest - x, floored at 0). The noise
// deviation is the RMS of |diff x| without its largest fifth, over sqrt 2.
ChannelShape channel_shape(std::span<const double> values, double rate_hz, double rest,
                           bool reversed);
// Pearson correlation of two equally long series; 0 when either is constant.
double correlation(std::span<const double> a, std::span<const double> b);
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
