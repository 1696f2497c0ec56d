#include "tactile/dsp/fur_preprocess.h"

#include <charconv>
#include <cmath>

#include "tactile/dsp/high_pass.h"
#include "tactile/error.h"

namespace tactile::dsp {

namespace {

std::vector<double> parse_peaks(const std::string& text, const std::string& where) {
  std::vector<double> peaks;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t end = std::min(text.find(',', start), text.size());
    const char* first = text.data() + start;
    const char* last = text.data() + end;
    while (first < last && *first == ' ') ++first;
    double value = 0.0;
    const auto [stop, error] = std::from_chars(first, last, value);
    if (error != std::errc() || stop != last || !std::isfinite(value))
      throw Error(where, "value " + std::to_string(peaks.size() + 1) + " '" +
                             text.substr(start, end - start) + "' is not a finite number");
    peaks.push_back(value);
    start = end + 1;
  }
  return peaks;
}

}  // namespace

std::vector<std::string> fur_preprocess_keys() {
  return {"cutoff_hz", "adc_max", "signal", "calibration_peak"};
}

FurPreprocessOptions fur_preprocess_options(const Parameters& parameters) {
  FurPreprocessOptions options;
  options.cutoff_hz = parameters.number("cutoff_hz", options.cutoff_hz);
  if (!(options.cutoff_hz > 0.0)) throw Error(parameters.where(), "cutoff_hz must be positive");
  options.adc_max = parameters.number("adc_max", options.adc_max);
  options.signal = parameters.text("signal", options.signal);
  if (options.signal != "auto" && options.signal != "falling" && options.signal != "rising")
    throw Error(parameters.where(),
                "signal=" + options.signal + ": expected falling, rising or auto");
  if (parameters.has("calibration_peak")) {
    options.calibration_peak = parameters.number("calibration_peak", 0.0);
    if (!(*options.calibration_peak > 0.0))
      throw Error(parameters.where(), "calibration_peak must be a positive number of counts");
  }
  return options;
}

const Stream& fur_stream(const Recording& recording) {
  const Stream* stream = recording.find_stream("skin");
  if (stream == nullptr && !recording.streams.empty()) stream = &recording.streams.front();
  if (stream == nullptr) throw Error(recording.id, "recording has no stream");
  if (!(stream->rate_hz > 0.0))
    throw Error(recording.id + " stream " + stream->name, "the sample rate must be positive");
  return *stream;
}

std::vector<double> fur_calibration_peaks(const Recording& recording, const SkinLayout& layout,
                                          const Stream& stream,
                                          const FurPreprocessOptions& options) {
  const auto columns = static_cast<size_t>(stream.channel_count());
  if (options.calibration_peak) return std::vector<double>(columns, *options.calibration_peak);
  const std::string where = recording.id + " metadata calibration_peak";
  const auto found = recording.metadata.find("calibration_peak");
  if (found == recording.metadata.end())
    throw Error(recording.id,
                "no calibration: the recording has no calibration_peak metadata; "
                "give calibration_peak=<counts>");
  const std::vector<double> per_channel = parse_peaks(found->second, where);
  if (per_channel.size() != layout.channels.size())
    throw Error(where, std::to_string(per_channel.size()) + " values for the " +
                           std::to_string(layout.channels.size()) + " channels of layout " +
                           layout.id);
  if (stream.channels.empty()) {
    if (columns != per_channel.size())
      throw Error(where,
                  "the stream's " + std::to_string(columns) + " unnamed columns do not match");
    return per_channel;
  }
  std::vector<double> peaks(columns, 0.0);
  for (size_t column = 0; column < columns; ++column) {
    const int channel = layout.channel_index(stream.channels[column]);
    if (channel < 0)
      throw Error(where,
                  "stream channel " + stream.channels[column] + " is not in layout " + layout.id);
    peaks[column] = per_channel[channel];
  }
  return peaks;
}

Recording fur_preprocess(const Recording& recording, const SkinLayout& layout,
                         const FurPreprocessOptions& options) {
  const Stream& raw = fur_stream(recording);
  const std::vector<double> peaks = fur_calibration_peaks(recording, layout, raw, options);
  bool rising = options.signal == "rising";
  if (options.signal == "auto") {
    const auto found = recording.metadata.find("signal");
    rising = found != recording.metadata.end() && found->second.find("rising") != std::string::npos;
  }
  // Spec §3.1: pressing lowers the ADC voltage, so u = 1023 - raw rises with pressure.
  const SampleMatrix pressure =
      rising ? raw.samples
             : SampleMatrix((static_cast<float>(options.adc_max) - raw.samples.array()).matrix());
  SampleMatrix normalised =
      normalise_to_calibration(high_pass_columns(pressure, options.cutoff_hz, raw.rate_hz), peaks);

  Recording result = recording;
  std::string dead_cells;
  for (size_t column = 0; column < peaks.size(); ++column)
    if (!(peaks[column] > 0.0)) {
      if (!dead_cells.empty()) dead_cells += ",";
      dead_cells += column < raw.channels.size() ? raw.channels[column] : std::to_string(column);
    }
  for (Stream& stream : result.streams) {
    if (stream.name != raw.name) continue;
    stream.samples = std::move(normalised);
    stream.units.assign(stream.channels.size(), "share of calibration peak");
    break;
  }
  result.metadata["preprocessing"] = std::string("fur: ") + (rising ? "raw" : "adc_max - raw") +
                                     ", high-pass " + std::to_string(options.cutoff_hz) +
                                     " Hz, divided by calibration peak, clamped to [0, 1]";
  if (!dead_cells.empty()) result.metadata["dead_cells"] = dead_cells;
  return result;
}

}  // namespace tactile::dsp
