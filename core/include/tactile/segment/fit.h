#pragma once
// A segmenter fitted to a few labelled touches (`tactile segment --fit-to LANE`, the
// workbench's Labels > Fit segmenter to my labels): the parameters of `adaptive` that best
// reproduce the touches someone labelled, with the event F1 they reach on labelled touches
// not used to choose them.
//
// Where the labels are scored: each recording's labelled stretch, from the first labelled
// touch's start to the last one's end (whoever labels ten touches labels every touch between
// them, and nothing after them is known); segments overlapping the stretch count, frames
// inside it count. The score of a parameter set is the summed event F1 (score_touches), then
// frame F1, over the stretches; ties go to the earlier set in the grid (adaptive's defaults
// come first). Held out: with two or more labelled recordings, each recording is held out in
// turn (by recording); with one, its touches are cut into three blocks of consecutive
// touches and each block's stretch is held out in turn (by time blocks). Each fold chooses
// on the other folds' touches and is scored on its own; the held-out score sums them.

#include <functional>
#include <string>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/labelstore/label.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/segment/scoring.h"

namespace tactile {

struct FitRecording {
  const Recording* recording = nullptr;
  const SkinLayout* layout = nullptr;
  std::vector<Label> touches;  // the lane's labels on this recording
};

struct SegmenterFit {
  std::string method = "adaptive";
  std::string params;   // chosen on every labelled touch, "key=value,..."
  TouchScore fitted;    // of those parameters on every labelled stretch
  TouchScore held_out;  // each fold's choice on its held-out touches, summed
  std::string folds;    // "by recording (3 folds)" or "by time blocks (3 folds)"
  int64_t touches = 0;
  int64_t candidates = 0;  // parameter sets tried
};

// The parameter sets tried, adaptive's defaults first: share x footprint x taxels x
// join_seconds (180).
std::vector<std::string> segmenter_fit_candidates();

// Throws tactile::Error when fewer than three touches are labelled in all, when a label lies
// outside its recording, or when a recording has no stream. `progress` gets the share done
// (0..1) and may throw to cancel. Never changes a label.
SegmenterFit fit_segmenter(const std::vector<FitRecording>& recordings,
                           const std::function<void(double)>& progress = {});

// The fit as a preset named `name`, fitted to `lane` (segment/presets.h).
struct SegmenterPreset;
SegmenterPreset fit_preset(const SegmenterFit& fit, const std::string& name,
                           const std::string& lane);

// The fit as text: the parameters, the held-out and fitted scores (as `--score` prints them).
std::string fit_report(const SegmenterFit& fit);
// One score as a line: "frame F1 0.906 (P 0.95 R 0.87), event F1 0.836 (74 of 92 touches,
// 11 false alarms), 5 split, 9 merged".
std::string touch_score_text(const TouchScore& score);

}  // namespace tactile
