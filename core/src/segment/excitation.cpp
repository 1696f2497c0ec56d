#include "tactile/segment/excitation.h"

#include <algorithm>
#include <cmath>

#include "tactile/error.h"

namespace tactile {

std::vector<int64_t> excitation_onsets(const Eigen::MatrixXd& deviation, int64_t watched_columns,
                                       double rate_hz, const dsp::FluxOptions& options) {
  dsp::ExcitationDetector detector(dsp::samples_of(options.window_s, rate_hz, 1),
                                   dsp::samples_of(options.refractory_quiet_s, rate_hz, 0),
                                   options.onset_threshold);
  std::vector<int64_t> onsets;
  const Eigen::Index watched = std::min<Eigen::Index>(watched_columns, deviation.cols());
  for (Eigen::Index n = 0; n < deviation.rows(); ++n) {
    // A NaN on a watched channel makes the sample neither quiet nor an onset.
    double largest = 0.0;
    for (Eigen::Index column = 0; column < watched; ++column) {
      const double magnitude = std::abs(deviation(n, column));
      if (std::isnan(magnitude)) {
        largest = magnitude;
        break;
      }
      largest = std::max(largest, magnitude);
    }
    if (detector.step(largest)) onsets.push_back(n);
  }
  return onsets;
}

std::vector<Label> segment_excitation(const Recording& recording, const SkinLayout& layout,
                                      const Parameters& parameters) {
  parameters.expect_only(dsp::flux_option_keys());
  const dsp::FluxOptions options = dsp::flux_options(parameters);
  const Recording processed = dsp::is_flux_preprocessed(recording)
                                  ? recording
                                  : dsp::preprocess_flux(recording, layout, options);
  const dsp::FluxChannels channels = dsp::flux_channels(layout);
  const Stream* stream = nullptr;
  for (const Stream& candidate : processed.streams)
    if (std::find(candidate.channels.begin(), candidate.channels.end(), channels.top_sum) !=
        candidate.channels.end())
      stream = &candidate;
  if (stream == nullptr)
    throw Error(recording.id, "no preprocessed flux stream (channel " + channels.top_sum + ")");
  if (!(stream->rate_hz > 0.0))
    throw Error(recording.id + " stream " + stream->name, "needs a regular sample rate");

  // The top layer's four channels, in order.
  const Eigen::Index count = stream->sample_count();
  Eigen::MatrixXd top(count, 4);
  for (size_t channel = 0; channel < 4; ++channel) {
    const auto found =
        std::find(stream->channels.begin(), stream->channels.end(), channels.top[channel]);
    if (found == stream->channels.end())
      throw Error(recording.id + " stream " + stream->name, "no channel " + channels.top[channel]);
    top.col(Eigen::Index(channel)) =
        stream->samples.col(found - stream->channels.begin()).cast<double>();
  }
  const int64_t window = dsp::samples_of(options.window_s, stream->rate_hz, 1);
  std::vector<Label> labels;
  for (int64_t onset : excitation_onsets(top, 4, stream->rate_hz, options)) {
    const int64_t end = std::min<int64_t>(onset + window, count);
    Label label;
    label.recording = recording.id;
    label.t0 = stream->time_of(onset);
    label.t1 =
        end < count ? stream->time_of(end) : stream->time_of(count - 1) + 1.0 / stream->rate_hz;
    label.region = "all";
    label.annotator = "segmenter:excitation";
    label.source = LabelSource::kSegmenter;
    labels.push_back(std::move(label));
  }
  return labels;
}

}  // namespace tactile
