#pragma once
// Recordings with touches known in advance, shared by the segmenter, fit and workbench tests:
// an operator who labels a double tap (two 0.3-s taps 0.5 s apart) as one touch.

#include <string>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/labelstore/label.h"
#include "tactile/layout/skin_layout.h"

namespace tactile::test {

// strip:8 at 50 Hz, 0/1: `pairs` double taps on sensor 3, the k-th from 2 + 4k s.
inline Recording double_tap_recording(const std::string& id, int pairs) {
  Recording recording;
  recording.id = id;
  recording.layout_id = "strip:8";
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = 50.0;
  for (const Channel& channel : load_layout("strip:8").channels)
    stream.channels.push_back(channel.name);
  stream.samples.setZero(100 + 200 * pairs, static_cast<Eigen::Index>(stream.channels.size()));
  for (int t = 100; t < 100 + 200 * pairs; ++t) {
    const int phase = (t - 100) % 200;
    stream.samples(t, 3) = phase < 15 || (phase >= 40 && phase < 55) ? 1.0f : 0.0f;
  }
  recording.streams = {stream};
  return recording;
}

// The first `pairs` double taps of double_tap_recording(recording, ...) as one touch each
// (2 + 4k s to 3.1 + 4k s), in `annotator`'s lane.
inline std::vector<Label> double_tap_touches(const std::string& recording, int pairs,
                                             const std::string& annotator = "ana") {
  std::vector<Label> labels;
  for (int k = 0; k < pairs; ++k) {
    Label label;
    label.recording = recording;
    label.t0 = (100 + 200 * k) / 50.0;
    label.t1 = (100 + 200 * k + 55) / 50.0;
    label.class_name = "double-tap";
    label.region = "all";
    label.annotator = annotator;
    label.source = LabelSource::kManual;
    labels.push_back(label);
  }
  return labels;
}

}  // namespace tactile::test
