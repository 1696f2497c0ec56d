#pragma once
// The smart-fur pipeline's preprocessing of a whole recording (spec §3.1-3.3): raw ADC
// counts -> pressure-increasing signal u = 1023 - raw -> first-order high-pass at 0.2 Hz ->
// division by each cell's calibration peak, clamped to [0, 1]. Shared by the `threshold`
// segmenter and the `fur` extractor.

#include <optional>
#include <string>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"

namespace tactile::dsp {

struct FurPreprocessOptions {
  double cutoff_hz = 0.2;       // spec §3.2
  double adc_max = 1023.0;      // 10-bit converter: u = adc_max - raw
  std::string signal = "auto";  // falling | rising | auto (metadata key "signal"; else falling)
  // One calibration peak for every cell, overriding the recording's metadata key
  // "calibration_peak" (one value per layout channel, comma-separated, in counts).
  std::optional<double> calibration_peak;
};
// Keys: cutoff_hz, adc_max, signal, calibration_peak.
FurPreprocessOptions fur_preprocess_options(const Parameters& parameters);
std::vector<std::string> fur_preprocess_keys();

// The stream the fur methods read: "skin", else the first. Throws when there is none or its
// rate is not positive.
const Stream& fur_stream(const Recording& recording);

// Calibration peak of each column of the fur stream: the option, else the metadata.
// Throws tactile::Error naming the recording and the metadata key when neither is usable.
std::vector<double> fur_calibration_peaks(const Recording& recording, const SkinLayout& layout,
                                          const Stream& stream,
                                          const FurPreprocessOptions& options);

// The recording with its fur stream replaced by v in [0, 1] (NaN where a sample was
// missing); metadata "preprocessing" says what was done and "dead_cells" lists the channels
// whose calibration peak is not positive (they read 0).
Recording fur_preprocess(const Recording& recording, const SkinLayout& layout,
                         const FurPreprocessOptions& options);

}  // namespace tactile::dsp
