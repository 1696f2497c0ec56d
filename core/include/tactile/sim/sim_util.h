#pragma once
// Small building blocks shared by the skin generators: ADC quantisation, contact envelopes,
// gesture order and stream set-up. Their random draws are tactile::Random (tactile/random.h).

#include <cstdint>
#include <string>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/labelstore/label.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/random.h"

namespace tactile::sim {

// An ADC: clamps `value` to [low, high] and rounds it to one of 2^bits levels; returns
// the level's value in the same units (saturation and quantisation as a device shows them).
float quantize(double value, double low, double high, int bits);

// Smooth contact envelope in [0, 1]: raised-cosine rise over `rise` s from `onset`, hold,
// raised-cosine fall over `fall` s ending at onset + duration. Zero outside.
double contact_envelope(double t, double onset, double duration, double rise, double fall);

// Minimum-jerk progress 0 -> 1 of `progress` in [0, 1] (clamped): how a hand moves from one place
// to another, starting and stopping smoothly (Flash & Hogan).
double minimum_jerk(double progress);

// Classes 0..count-1, each `repetitions` times, in a random order where no class
// follows itself when that can be avoided.
std::vector<int> shuffled_classes(int count, int repetitions, Random& random);

// A stream whose channels and units are the layout's, with `samples` rows of zeros.
Stream make_stream(const SkinLayout& layout, const std::string& name, double rate_hz,
                   int64_t samples);

// A simulator's ground truth for one touch: its span, class and region, annotator "simulator",
// source kGroundTruth, confidence 1.
Label ground_truth_label(const std::string& recording, double t0, double t1,
                         const std::string& class_name, const std::string& region);

// Standard metadata of a simulated recording.
Metadata simulated_metadata(const std::string& skin, int subject, int trial,
                            const std::string& side, const std::string& condition);

}  // namespace tactile::sim
