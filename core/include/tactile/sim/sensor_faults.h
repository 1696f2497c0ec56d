#pragma once
// Sensor faults laid over a simulated recording, as an uncalibrated skin shows them: stuck and
// dead taxels, a slow drift of each taxel's rest, crosstalk from neighbours, per-taxel offsets
// and a hand resting on the skin between the labelled touches (not labelled). Applies to any
// skin's recording whose first stream has the layout's channels; positions come from the
// layout. Sizes are shares of each channel's touch swing ("peak": its largest excursion
// from its median in the clean recording; a channel no touch reached gets the typical peak
// of those that were touched, with their usual sign). docs/SIMULATION.md, "Sensor faults".

#include <cstdint>
#include <string>

#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"
#include "tactile/sim/simulator.h"

namespace tactile {

struct SensorFaults {
  int stuck = 0;           // channels stuck, from a random moment on, at a value inside their swing
  int dead = 0;            // channels reading 0 throughout
  double drift = 0.0;      // rest drift over the recording, share of the peak (random sign, slow)
  double crosstalk = 0.0;  // share of the neighbours' mean change each channel picks up
  double offsets = 0.0;    // per-channel rest offset, uniform within +-offsets x peak
  double rest = 0.0;       // chance that a hand rests on the skin in a pause of >= rest_gap s
  double rest_level = 0.15;  // the resting hand's press, share of the peak
  double rest_patch = 0.3;   // share of the taxels under the resting hand
  double rest_gap = 2.0;     // shortest pause (s) between labels that can hold a resting hand

  bool any() const;
};

// "none" (or ""), "realistic" (stuck=2, dead=1, drift=0.3, crosstalk=0.05, offsets=1, rest=0.6)
// or key=value pairs of the fields above, which may follow "realistic," to change some.
// tactile::Error naming `where` for an unknown key or a value out of range.
SensorFaults parse_sensor_faults(const std::string& text, const std::string& where);

// Lays the faults over trial.recording's first stream; the labels are kept. Deterministic by
// (seed, subject, trial); stuck and dead channels together are at most an eighth of the
// channels (at least one when asked for). The recording's metadata gains "faults".
void apply_sensor_faults(SimulatedTrial& trial, const SkinLayout& layout,
                         const SensorFaults& faults, uint64_t seed, int subject, int trial_index);

}  // namespace tactile
