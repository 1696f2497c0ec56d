#pragma once
// Segmenter "adaptive": touches on skins with no calibration (grid, strip, other people's
// data), with no parameters. A touch is a gesture instance as people label it: a grab, a
// punch, a stroke, a tickle; contacts separated by short releases (a tickle's fingers, a
// stroke that lifts and lands again, a squeeze that eases) are one touch (docs/SEGMENTERS.md).
// Per channel, from the recording itself:
// - stuck: on a noisy channel (its value changes in at least half of its frames), a run of one
//   unchanging value for stuck_seconds (1) or more is missing; a noiseless sensor (binary,
//   integer steps, clipped at zero) holds its rest for long by nature and is never "stuck";
// - direction: touches move a channel to the side with the longer tail (twice the other's
//   0.5 % tail) once a running median over opening_seconds is taken off, or both ways
//   (oscillating films); a channel with neither takes the skin's direction (nine in ten);
// - rest of a one-way channel: medians of 0.25 s blocks, then their lower envelope (upper for
//   channels that touches lower), a morphological opening over opening_seconds (4), mirrored
//   through each end of the recording; opening_seconds=0 and two-way channels: the running
//   quantile of the block medians over baseline_seconds (20), away from the touches;
// - excursion: the residual, one-sided when the direction is known, closed over
//   envelope_seconds (0.03); noise sigma = 1.4826 x the MAD of the frame-to-frame differences over
//   sqrt 2 (0 for a noiseless sensor); a noisy channel with a tenth of the median noisy channel's
//   sigma, changing every frame, is stuck under a drifting offset and never counts;
// - band: margin (2) x 3 sigma, or `share` (0.2) of the touch amplitude of the channel's kind,
//   whichever is higher. A kind is the layout's modality and unit (one scale); its amplitude
//   is the 95th percentile of its channels' peaks (the highest excursion a channel holds for
//   min_seconds) among channels that left their noise band. So a binary sensor is on when it
//   is on, an 8-bit grid past a fifth of its full press, a noisy analog skin past its noise.
// A frame is a touch frame when as many channels are past their band as a tenth (`footprint`)
// of a touch's footprint on this skin (the median number of channels on, over the frames
// with any on), `taxels` (2) at least; one channel `alone` (2) times past its band
// stands for `taxels`. A contact is a run of touch frames, its edges moved out while half as
// many channels stay on. Contacts whose release is at most join_seconds are one touch; by
// default (join_seconds < 0) the join is a quarter of the median contact's length, at least
// one frame and at most half a second: short lifts inside a gesture join, a release as long
// as a contact (repeated taps, pulses) separates. Touches of at least min_seconds (0.05), cut
// at max_seconds (10). Note "quiet" / "open" / "forced". quiet_seconds is join_seconds's old
// name. Region: the layout group whose channels went furthest past their bands over the
// touch, else "all".

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/labelstore/label.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"
#include "tactile/signal/sample_source.h"

namespace tactile {

std::vector<Label> segment_adaptive(const Recording& recording, const SkinLayout& layout,
                                    const Parameters& parameters);
// The same from a source read one channel at a time (twice), so that a recording file is never
// held whole: the same labels as segment_adaptive(read_all(source), ...). `step(share)` is
// called after each channel read and may throw to stop (a cancelled job).
std::vector<Label> segment_adaptive(const SampleSource& source, const SkinLayout& layout,
                                    const Parameters& parameters,
                                    const std::function<void(double)>& step = {});

struct AdaptiveScan;

// adaptive in two halves, for trying many parameter sets on one recording (fitting): the
// constructor does the slow half (rest, noise, excursions) with the parameters that shape it;
// segments() decides with the rest (adaptive_fast_parameters()) as segment_adaptive would
// with both sets together.
class AdaptiveSegmenter {
 public:
  AdaptiveSegmenter(const Recording& recording, const SkinLayout& layout, const Parameters& slow);
  std::vector<Label> segments(const Parameters& fast) const;

 private:
  std::shared_ptr<const AdaptiveScan> scan_;
  Parameters slow_;
};

// taxels, alone, share, footprint, join_seconds, quiet_seconds, max_seconds.
const std::vector<std::string>& adaptive_fast_parameters();

}  // namespace tactile
