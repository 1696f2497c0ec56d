#pragma once
// How a skin view colours raw device values. Many skins report a large rest level with
// a small change under touch (capacitive counts, a pressure matrix's pull-up, a piezo's
// bipolar swing), so a view shows the size of the change from each taxel's rest level,
// scaled to the changes the recording actually contains.

#include <vector>

#include "tactile/io/recording.h"
#include "tactile/signal/sample_source.h"

namespace tactile {

struct RestScale {
  std::vector<float> rest;  // per entry of `columns`: the column's rest level (NaN when absent)
  std::vector<float> noise_band;  // per entry: changes up to this size are noise (3 sigma)
  double max_change = 1.0;        // change beyond the noise band that maps to the top of the scale
};

// From up to `probes` evenly spaced samples of each column: rest = median (touches are
// brief against a recording), noise sigma = 1.4826 x median absolute deviation, noise
// band = 3 sigma. The scale's top = the 99th percentile of the changes that exceed their
// band, so a quiet taxel stays dark, a touch shows whatever the skin's rest level, and a
// single spike does not wash the map out. Columns < 0 are skipped.
RestScale rest_scale(const Stream& stream, const std::vector<int>& columns, int probes = 2048);

// The same through a SampleSource, reading no more than a bounded number of samples:
// a source of at most kRestScaleExactSamples samples is probed as above; a longer one is
// cut into up to `probes` buckets of whole coarse blocks, equal in samples, whose min/max
// come from its coarse data (a file's overview), and then rest = median of the bucket
// centres, noise band = median of the bucket half-ranges (about 3 sigma for a few hundred
// samples of Gaussian noise), and a bucket's change = its farthest value from rest less the
// band.
inline constexpr int64_t kRestScaleExactSamples = 32768;
RestScale rest_scale(const SampleSource& source, const std::vector<int>& columns,
                     int probes = 2048);

// The scale of a live stream, learnt again over what its buffer holds as it arrives: rest_scale
// of `source`, whose top never falls below `previous_top` (a touch once seen keeps its place on
// the scale) nor below kQuietTopBands times the median noise band: before the first touch the
// top of a quiet skin's changes was its noise (+1 where a replay of the same samples read
// +198), and the noise lit taxels at random.
inline constexpr double kQuietTopBands = 10.0;
RestScale live_rest_scale(const SampleSource& source, const std::vector<int>& columns,
                          double previous_top);

// max(0, |value - rest| - noise band) per entry; NaN stays NaN.
std::vector<float> change_from_rest(const std::vector<float>& values, const RestScale& scale);

// Where the signal starts or stops moving near t (a dragged label edge snaps there): the
// edges between `columns` equal time columns of [t - tolerance, t + tolerance] where "some
// channel of `channels` (-1: absent) is outside its noise band of `scale`" flips, read as
// min/max from the source.
std::vector<double> activity_edges(const SampleSource& source, const std::vector<int>& channels,
                                   const RestScale& scale, double t, double tolerance,
                                   int columns = 24);

// The instant in [t0, t1) (at most `max_samples` read from t0) where the channels (-1:
// absent) together differ most from their rest levels, as the sum of |value - rest|: where a
// touch lights the skin most. The middle of the span when nothing is read.
double peak_change_time(const SampleSource& source, const std::vector<int>& channels,
                        const RestScale& scale, double t0, double t1, int64_t max_samples);

}  // namespace tactile
