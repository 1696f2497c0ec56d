#pragma once
// Segmenter "adaptive": for skins with no calibration (grid, strip, other people's data).
// Touches are contacts: two that follow each other are two, however short the release between
// them (issue 26). Per channel, from the recording itself:
// - stuck or dead: runs of one unchanging value for stuck_seconds (1) or more count as missing,
//   and a channel with nothing else never counts;
// - direction: touches move a channel to the side with the longer tail (twice the other's
//   0.5 % tail) once a running median over opening_seconds is taken off, or both ways
//   (oscillating films); a channel with neither (a taxel no touch reached) takes the skin's
//   direction, the one three quarters of the channels with a direction share;
// - rest of a one-way channel: medians of 0.25 s blocks, then their lower envelope (upper for
//   channels that touches lower), a morphological opening over opening_seconds (4; a running
//   minimum then maximum, the block medians mirrored through each end of the recording), so
//   drift is followed to the first and last frame and a skin touched most of the time keeps
//   its rest from its releases; a press held longer than the window becomes the rest.
//   opening_seconds=0, and channels moved both ways: the running quantile of the block medians
//   over baseline_seconds (20), on the side away from the touches (0.25 or 0.75; 0.5 both
//   ways);
// - noise: sigma = 1.4826 x the MAD of the residual; the excursion z = residual / sigma, one-
//   sided when the direction is known, closed over envelope_seconds (0.03: a running maximum
//   then minimum) so oscillations keep their level and edges stay put. A channel with a tenth
//   of the median channel's sigma or less (stuck under a drifting offset) never counts.
// A frame is off rest when `taxels` (2) channels exceed margin (2) x 3 sigma, or one exceeds
// `alone` (2) times that. A run of such frames, bridged over gaps up to quiet_seconds (0.02),
// is a touch only where `taxels` channels (or one, alone) reach the touch level: `level` (0.3)
// times the channel's peak z (the highest it holds for min_seconds) or the median of those
// over moving channels, whichever is higher. A hand resting between touches is low (a sixth
// of a touch's press), so it stays below, however broad and long; crosstalk follows a touch,
// so it never stands alone. A run is split at each release: between two touch-level stretches, at
// the lowest total excursion; and wherever the total excursion dips below `dip` (0.2) times the
// smaller of its highest values on either side (recursively). Segments of at least min_seconds
// (0.05), cut at max_seconds (10). Note: "quiet" / "open" / "forced". Parameters: margin, taxels,
// alone, level, dip, baseline_seconds, opening_seconds, envelope_seconds, stuck_seconds,
// quiet_seconds, max_seconds, min_seconds. quiet_seconds=0.25,dip=0 keeps contacts less than a
// quarter second apart in one segment (gesture-level labels). Region: the layout group whose
// channels moved most over the segment, else "all".

#include <vector>

#include "tactile/io/label.h"
#include "tactile/io/recording.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"

namespace tactile {

std::vector<Label> segment_adaptive(const Recording& recording, const SkinLayout& layout,
                                    const Parameters& parameters);

}  // namespace tactile
