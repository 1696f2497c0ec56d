#pragma once
// The TSA pipeline's preprocessing of a whole recording (spec §2.1-2.3): raw converter
// counts -> eq. (3) IIR average -> per-sheet baseline and per-channel trigger -> contact
// values (change from baseline where it clears the threshold, else 0). Shared by the
// `frame-edge` segmenter and the `tsa_event` extractor so both see the same contacts.

#include <cstdint>
#include <string>
#include <vector>

#include "tactile/dsp/contact_trigger.h"
#include "tactile/io/recording.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"

namespace tactile::dsp {

// One 4x4 sheet of the layout, in the sheet's own coordinates (spec §2.1: x = column to
// the right, y = row downwards, unit = pad pitch).
struct TsaSheet {
  std::string id;               // the "sheet" group, e.g. "m03.s2"
  std::string location;         // the "location" group holding it, e.g. "arm-left"; "" when none
  int code = 0;                 // spec §2.9 location code: 1-based order among the layout's sheets
  std::vector<int64_t> taxels;  // taxel ids, in the group's order
  std::vector<int> columns;     // stream column of each pad
  std::vector<Point2> positions;  // pad positions in pitch units, (0, 0) = top-left pad
  Point2 centre;                  // centre of the pad grid, (1.5, 1.5) on a 4x4 sheet
};

// The layout's groups of kind "sheet" mapped onto a stream's columns. Throws tactile::Error
// naming the layout when it has no sheet, or naming a channel the stream lacks.
std::vector<TsaSheet> tsa_sheets(const SkinLayout& layout, const Stream& stream);

struct TsaPreprocessOptions {
  int64_t iir_window = 4;      // eq. (3) N (spec default); 1 when the counts are already smoothed
  std::string touch = "auto";  // rising | falling | auto (the recording's front_end metadata)
  ContactTriggerOptions trigger;  // rate and direction are filled from the recording
};
// Keys: iir_n, touch, baseline_seconds, noise_sigmas, min_threshold, hold_off_frames.
TsaPreprocessOptions tsa_preprocess_options(const Parameters& parameters);
std::vector<std::string> tsa_preprocess_keys();

// The stream the TSA methods read: "skin", else the first. Throws when there is none or its
// rate is not positive.
const Stream& tsa_stream(const Recording& recording);
// Whether a touch raises the counts: `touch`, or for "auto" the metadata key front_end
// ("rising"/"falling" in its text); without it the spec's LC-count reading (falling).
bool tsa_touch_rises(const Recording& recording, const std::string& touch);

// The recording with its TSA stream replaced by contact values (counts above baseline,
// 0 where inactive, NaN where the sample was missing); metadata key "preprocessing" says
// what was done.
Recording tsa_preprocess(const Recording& recording, const SkinLayout& layout,
                         const TsaPreprocessOptions& options);

}  // namespace tactile::dsp
