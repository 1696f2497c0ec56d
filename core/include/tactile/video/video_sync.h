#pragma once
// Proposing a video's offset: the video's motion energy (mean absolute difference of
// consecutive frames, optionally within a region) correlated with the skin's activity over a
// range of lags. The best lag is offered with a confidence; the user accepts or rejects it.

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace tactile {

class VideoFile;
class SampleSource;

// A region of the picture in fractions of its width and height.
struct VideoRegion {
  double x = 0, y = 0, width = 1, height = 1;
};

// A series sampled on a regular grid: value k at start + k / rate.
struct ActivitySeries {
  double start = 0;
  double rate = 0;
  std::vector<double> values;
};

// The video's motion energy at `rate` samples per second of video time: per pair of
// consecutive frames the mean absolute difference of their luma (within `region`) beyond the
// pair's median absolute difference (the still pixels' noise, a key frame's re-encoding, an
// exposure step), in luma levels (0..255), placed at the later frame's time; per grid step the
// mean of the pairs ending in it. `video` opened grey and small (VideoOpenOptions{.max_width =
// 160, .grey = true}). `progress(fraction)` is called now and then (JobProgress::steps); a job's
// cancel (cancel_requested()) stops it with an Error.
ActivitySeries motion_energy(VideoFile& video, double rate, std::optional<VideoRegion> region,
                             const std::function<void(double)>& progress = {});

// The skin's activity at `rate` samples per second of recording time: per grid step, over every
// channel, the summed absolute change of the channel's moving mean over a quarter of a step
// (noise averages out, a touch's change stays whole), each channel scaled by its own noise so
// that one loud channel does not drown the rest.
ActivitySeries skin_activity(const SampleSource& source, double rate,
                             const std::function<void(double)>& progress = {});

// When propose_offset is sure (docs/VIDEO.md, "Synchronising"):
// - the video's motion energy (luma levels, 0..255) varies by at least kMinMotion (standard
//   deviation over the overlap): a still picture's codec noise stays far below it;
// - some step of the skin's activity reaches kTouchOverMedian times its median (the noise of
//   the quiet skin summed over its channels);
// - the overlap at the best offset lasts kMinOverlapSeconds;
// - the correlation at the best offset reaches kMinCorrelation, and the confidence
//   (best - rival) / (1 - rival), the rival the best other peak beyond kSeparateSeconds,
//   reaches kSureConfidence.
inline constexpr double kMinMotion = 0.05;
inline constexpr double kTouchOverMedian = 3.0;
inline constexpr double kMinOverlapSeconds = 10.0;
inline constexpr double kMinCorrelation = 0.25;
inline constexpr double kSureConfidence = 0.2;
inline constexpr double kSeparateSeconds = 1.0;
// A channel's noise in skin_activity is floored at this fraction of the median channel's.
inline constexpr double kNoiseFloorOfTypical = 0.25;

struct SyncProposal {
  double offset = 0;       // the proposed VideoAttachment::offset (rate 1)
  double correlation = 0;  // normalised cross-correlation at the best lag, -1..1
  double confidence = 0;   // 0..1: how far the best peak stands above the next one
  bool sure = false;       // confidence high enough to offer the offset without a warning
  std::string why;         // when not sure: what is missing ("the video shows no motion", ...)
};

// The offset in [centre - max_lag, centre + max_lag] at which the skin's activity and the
// video's motion energy agree best.
SyncProposal propose_offset(const ActivitySeries& skin, const ActivitySeries& motion, double centre,
                            double max_lag);

}  // namespace tactile
