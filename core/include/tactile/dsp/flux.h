#pragma once
// Flux sensor preprocessing (spec §5.2-5.5, paper 004): causal moving average, ratiometric
// normalisation against a baseline V0 re-sampled each minute when the sensor is quiet,
// virtual sum channels, and the excitation state shared with the segmenter.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"

namespace tactile::dsp {

// Settings of the flux chain, in seconds where the spec gives seconds; read from
// parameters with these keys (defaults = spec values).
struct FluxOptions {
  int64_t average_window = 10;      // average_window: N of §5.2
  double onset_threshold = 0.05;    // onset_threshold: θ_on of §5.5 (5 % change)
  double window_s = 5.0;            // window_s: analysis window L / fs of §5.5
  double refractory_quiet_s = 0.5;  // refractory_quiet_s: quiet time before a new onset
  double baseline_period_s = 60.0;  // baseline_period_s: V0 re-sampling period of §5.3
  double baseline_quiet_s = 1.0;    // baseline_quiet_s: quiet time a re-sample needs
  // baseline_settle: how far the signal may still move during that quiet time (relative
  // change between the means of its two halves). Not in the spec: see ratiometric_deviation.
  double baseline_settle = 0.001;
  double steady_s = 0.5;  // steady_s: L_s / fs, end of window averaged (§5.6)
};
std::vector<std::string> flux_option_keys();
// Throws tactile::Error naming the key when a value is out of range. Does not reject
// other keys (the caller knows its own).
FluxOptions flux_options(const Parameters& parameters);
// Seconds to a whole number of samples at `rate_hz`, at least `minimum`.
int64_t samples_of(double seconds, double rate_hz, int64_t minimum);

// Flux §5.2: y[n] = (1/N_n) Σ_{k=n-N_n+1}^{n} x[k], N_n = min(N, n+1). A non-finite sample
// makes the N outputs whose window holds it NaN.
Eigen::VectorXd causal_moving_average(const Eigen::Ref<const Eigen::VectorXd>& x, int64_t window);

// Spec §5.5 as a sample-by-sample state machine: an onset is the first sample whose
// largest |e| over the watched channels exceeds θ_on while armed; it then disarms until
// the window of L samples has ended and every watched channel has been below θ_on for the
// quiet time. Starts armed.
class ExcitationDetector {
 public:
  ExcitationDetector(int64_t window_samples, int64_t quiet_samples, double threshold);
  // Feeds max_c |e_c[n]| of the next sample (NaN counts as neither quiet nor an onset);
  // true when this sample is an onset.
  bool step(double largest_magnitude);
  // True from an onset until the detector re-arms (window plus refractory quiet).
  bool in_progress() const { return !armed_; }

 private:
  int64_t window_samples_;
  int64_t quiet_samples_;
  double threshold_;
  int64_t index_ = 0;  // of the next sample
  int64_t window_end_ = 0;
  int64_t quiet_run_ = 0;
  bool armed_ = true;
};

struct RatiometricResult {
  Eigen::MatrixXd deviation;              // e = y / V0 - 1, one column per input column
  std::vector<int64_t> baseline_samples;  // where V0 was taken: start-up, then re-samples
  std::vector<bool> invalid;              // per column: some V0 <= 0 (its e held at 0 there)
};

// Flux §5.3: e[n] = y[n] / V0 - 1 for every column of the averaged signals `averaged`.
// V0 = y[N-1] (the first full window; the first finite y after it for a column whose
// y[N-1] is not finite), applied from sample 0; then re-sampled every baseline period once
// no excitation is in progress (detector on the first `onset_columns` columns) and every
// column has had |e| < θ_on for the baseline quiet time, postponed until that holds. A
// re-sample applies from its own sample on.
// Beyond the spec, a re-sample also waits until every column has settled: the means of the
// two halves of the quiet time differ by less than baseline_settle · V0; the new V0 is the
// mean of the early half (y[n] may already carry the start of the next touch, under θ_on). Without
// it, V0 is taken on the slow relaxation tail (τ ≈ 7 s, under θ_on long before it ends), each such
// V0 up to θ_on above the last, until the resting e sits below -θ_on: the quiet test then
// never passes again, no excitation re-arms the detector, and every later event is lost. V0 <= 0
// marks the column invalid and holds its e at 0 while that V0 lasts.
RatiometricResult ratiometric_deviation(const Eigen::MatrixXd& averaged, double rate_hz,
                                        int64_t onset_columns, const FluxOptions& options);

// Flux layout channel order (spec §5.4): top 1-4, top sum, bottom 1-4, bottom sum. The real
// channels are those owned by a taxel; the sums are the two channels no taxel owns.
struct FluxChannels {
  std::vector<std::string> top;     // x1..x4
  std::string top_sum;              // x_sum
  std::vector<std::string> bottom;  // y1..y4
  std::string bottom_sum;           // y_sum
};
// Throws tactile::Error naming the layout when it is not laid out as §5.4 says.
FluxChannels flux_channels(const SkinLayout& layout);

// Metadata key and value that mark a recording as run through preprocess_flux.
inline constexpr const char* kPreprocessedKey = "preprocessed";
inline constexpr const char* kFluxPreprocessed = "flux";
bool is_flux_preprocessed(const Recording& recording);

// The whole chain on the stream holding the real channels ("skin", or the first stream
// with the first top channel): moving average, ratiometric deviation e, virtual sums
// (flux §5.4: e_sum[n] = Σ_c e_c[n] over a layer). The stream is replaced by one with the
// layout's 10 channels in layout order, values e (unit "1"); any sum columns it had are
// recomputed. Other streams are kept. Metadata: preprocessed=flux,
// flux.baseline_samples=<count>, flux.invalid_channels=<names> when any. Throws
// tactile::Error naming the stream for a missing real channel or an irregular stream.
Recording preprocess_flux(const Recording& recording, const SkinLayout& layout,
                          const FluxOptions& options);

}  // namespace tactile::dsp
