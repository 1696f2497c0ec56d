#pragma once
// The raw-sample pipeline, for any layout: each channel of one modality resampled to a fixed
// number of points over the segment, referenced to the channel's rest level and scaled, so
// that a classifier on raw samples is one command like any other (issue 26).
//
// Parameters: modality = a layout modality, "display" or "all" (default: every channel);
// stream = the stream to read (default: the first); samples = points per channel (default
// 32, at least 2); baseline = rest (default: minus the channel's rest level over the
// recording, generic's quiet_level) or none; scale = none | global (default) | channel;
// series = channels (default: each chosen channel) | summary (raw_summary below) | auto
// (summary above kGridTaxelsForGeneric taxels; rocket's default).
//
// Where each scaling happens. A pipeline turns one segment into one row and may use the
// whole recording (preprocess()), never the other rows of the table:
//   none     the channel's own units;
//   global   one factor per recording and modality (channels of one modality share their
//            units): the 99th percentile of |x - baseline| over every sample of every chosen
//            channel of that modality in the recording;
//   channel  one factor per channel and recording: the 99th percentile of that channel's
//            |x - baseline| over the recording.
// Per-feature standardisation (each column z-scored) needs the other rows, so it belongs
// to the classifier: every classifier that standardises (ridge, the SVMs, k-NN with
// standardize) fits it on the training fold only. scale=feature is refused with that
// explanation. A factor of 0 (a flat recording) is taken as 1.

#include <Eigen/Core>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "tactile/features/feature_extractor.h"
#include "tactile/layout/skin_layout.h"

namespace tactile {

// `values` resampled to `count` points (count >= 2) by linear interpolation over the span of
// the samples: point k sits at sample position k (n - 1) / (count - 1), so the first and
// last points are the first and last samples. One sample gives a constant; none, zeros.
std::vector<double> resample_linear(std::span<const double> values, int64_t count);

// How raw and rocket read a segment: which channels, its reference and scale, and whether
// the series are the channels themselves or the layout-driven summary (raw_summary).
enum class RawScale { none, global, channel };
enum class RawSeries { channels, summary, automatic };
struct RawReading {
  std::string modality = "all";  // a layout modality, "display" or "all"
  std::string stream;            // empty: the recording's first stream
  int64_t samples = 32;          // points per channel after resampling
  bool subtract_rest = true;     // baseline=rest
  RawScale scale = RawScale::global;
  RawSeries series = RawSeries::channels;    // series = channels | summary | auto
  std::string levels_stream = "raw.levels";  // what preprocess() adds (rest, scale rows)
};
// Reads and checks modality, stream, samples (>= minimum_samples), baseline, scale and
// series (default `default_series`: "channels" or "auto"); Error naming the parameter
// otherwise.
RawReading read_raw_parameters(const Parameters& parameters, int64_t default_samples,
                               int64_t minimum_samples,
                               const std::string& default_series = "channels");
// The layout channels of the reading's modality, in layout order; Error naming the modality
// when the layout has none of it.
std::vector<int> raw_channels(const SkinLayout& layout, const RawReading& reading,
                              const std::string& where);
// The stream the reading reads (pipeline_stream); Error naming it when missing, or when its
// channels are not the layout's (layout_columns).
const Stream& raw_stream(const Recording& recording, const SkinLayout& layout,
                         const RawReading& reading);
// Each chosen layout channel's column in the stream (layout_columns); -1 for a channel the stream
// lacks (flux's virtual sums, which its own preprocessing computes), whose values then read as 0.
// Error when the stream holds none of them.
std::vector<int64_t> raw_stream_columns(const Stream& stream, const SkinLayout& layout,
                                        const std::vector<int>& channels);
// The recording with a two-row stream `levels_stream` added: per channel its rest level
// (row 0; 0 for baseline=none) and its scale factor (row 1), one column per layout channel.
Recording add_raw_levels(const Recording& recording, const SkinLayout& layout,
                         const RawReading& reading, const std::string& where);
// The segment of every chosen channel, resampled, referenced and scaled: samples x channels.
// Empty with `skip_reason` set for a segment without samples or with a non-finite sample.
// Without the levels stream (no preprocess()), rest 0 and scale 1.
Eigen::MatrixXd raw_segment(const SegmentInput& input, const RawReading& reading,
                            const std::vector<int>& channels, std::string& skip_reason);

// The summary series (series=summary; series=auto picks it when the chosen channels sit on
// more than kGridTaxelsForGeneric taxels, as generic's whole-grid switch). A touch moves a
// few of hundreds of channels, in a different place each time; these series are the same
// wherever it lands, plus coarse group sums that say where it landed. Per modality of the chosen
// channels, from the referenced, scaled points x (e = |x|, the excursion):
//   M.total        sum of e over the modality's channels (the whole-skin total);
//   M.peak         largest e over them;
//   M.active       share of them with e above 0.2 of the segment's largest e (contact area);
//   M.centroid_x, M.centroid_y   the e-weighted centre of those active channels' taxels on
//                  the map, minus its mean over the segment (0 where none is active);
//   M.KIND.1..3    per group kind of the layout (sheet, row, body-part...): the sums of e
//                  over each group's channels, the three largest over the segment first;
//   M.GROUP        for kinds of at most kRawSummaryPlacedGroups groups, each group's sum of
//                  e as well, in layout order: where the touch was, coarsely (robovie's
//                  body parts, fur's rows; not tsa's 42 sheets, which would spread a touch
//                  over series the kernels rarely draw);
//   M.top.1..8     the channels themselves (x, signed), the eight of largest sum x^2 first.
// Fewer groups or channels than that: fewer series.
struct RawSummaryPlan {
  std::vector<std::string> names;  // one per series
  std::vector<std::string> descriptions;
  // The groups of one kind, as positions in their block's channels.
  struct Kind {
    std::vector<std::string> ids;
    std::vector<std::vector<int>> groups;
    int ranked = 0;       // min(kRawSummaryGroups, groups)
    bool placed = false;  // groups <= kRawSummaryPlacedGroups: each group's sum too
  };
  // Per modality: its channels' positions in the chosen channels, their taxels' map
  // positions, the group kinds in order of first appearance, the ranked channel count.
  struct Block {
    std::string modality;
    std::vector<int> members;
    std::vector<Point2> positions;
    std::vector<Kind> kinds;
    int top_channels = 0;
  };
  std::vector<Block> blocks;
};
inline constexpr int kRawSummaryGroups = 3;
inline constexpr size_t kRawSummaryPlacedGroups = 24;
inline constexpr int kRawSummaryChannels = 8;
inline constexpr double kRawSummaryActive = 0.2;
// True when the reading reads the summary for these channels of the layout.
bool raw_reads_summary(const SkinLayout& layout, const RawReading& reading,
                       const std::vector<int>& channels);
RawSummaryPlan plan_raw_summary(const SkinLayout& layout, const std::vector<int>& channels);
// points: samples x chosen channels (raw_segment); returns samples x plan.names.size().
Eigen::MatrixXd raw_summary(const RawSummaryPlan& plan, const Eigen::MatrixXd& points);

// Throws tactile::Error naming the parameter when unknown or bad.
std::unique_ptr<FeatureExtractor> make_raw_extractor(const Parameters& parameters);

}  // namespace tactile
