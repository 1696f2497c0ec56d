#include "tactile/dsp/tsa_preprocess.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "tactile/dsp/iir_average.h"
#include "tactile/error.h"

namespace tactile::dsp {

std::vector<TsaSheet> tsa_sheets(const SkinLayout& layout, const Stream& stream) {
  std::map<std::string, int> column_of_channel;
  for (size_t column = 0; column < stream.channels.size(); ++column)
    column_of_channel[stream.channels[column]] = static_cast<int>(column);
  const bool unnamed = stream.channels.empty() &&
                       stream.channel_count() == static_cast<int64_t>(layout.channels.size());

  std::vector<TsaSheet> sheets;
  for (const Group& group : layout.groups) {
    if (group.kind != "sheet") continue;
    TsaSheet sheet;
    sheet.id = group.id;
    sheet.code = static_cast<int>(sheets.size()) + 1;
    if (!group.taxels.empty()) {
      const std::vector<const Group*> locations =
          layout.groups_of(group.taxels.front(), "location");
      if (!locations.empty()) sheet.location = locations.front()->id;
    }
    std::vector<Point2> map_positions;
    for (int64_t id : group.taxels) {
      const Taxel* taxel = layout.find_taxel(id);
      if (taxel == nullptr || taxel->channels.empty() || taxel->channels.front() < 0)
        throw Error("layout " + layout.id,
                    "sheet " + group.id + ": taxel " + std::to_string(id) + " has no channel");
      const int channel = taxel->channels.front();
      int column = channel;
      if (!unnamed) {
        const auto found = column_of_channel.find(layout.channels[channel].name);
        if (found == column_of_channel.end())
          throw Error(
              "stream " + stream.name,
              "no column for channel " + layout.channels[channel].name + " of sheet " + group.id);
        column = found->second;
      }
      sheet.taxels.push_back(id);
      sheet.columns.push_back(column);
      map_positions.push_back(taxel->position);
    }
    if (map_positions.empty())
      throw Error("layout " + layout.id, "sheet " + group.id + " has no taxels");
    // Pitch = the nearest spacing of two pads; positions relative to the top-left pad.
    double pitch = 0.0;
    Point2 low = map_positions.front(), high = map_positions.front();
    for (size_t a = 0; a < map_positions.size(); ++a) {
      low = {std::min(low.x, map_positions[a].x), std::min(low.y, map_positions[a].y)};
      high = {std::max(high.x, map_positions[a].x), std::max(high.y, map_positions[a].y)};
      for (size_t b = a + 1; b < map_positions.size(); ++b) {
        const double distance = std::hypot(map_positions[a].x - map_positions[b].x,
                                           map_positions[a].y - map_positions[b].y);
        if (distance > 0.0 && (pitch == 0.0 || distance < pitch)) pitch = distance;
      }
    }
    if (pitch == 0.0) pitch = 1.0;  // a one-pad sheet: any unit will do
    for (const Point2& position : map_positions)
      sheet.positions.push_back({(position.x - low.x) / pitch, (position.y - low.y) / pitch});
    sheet.centre = {0.5 * (high.x - low.x) / pitch, 0.5 * (high.y - low.y) / pitch};
    sheets.push_back(std::move(sheet));
  }
  if (sheets.empty())
    throw Error("layout " + layout.id,
                "has no group of kind \"sheet\" (the TSA methods need sheets)");
  return sheets;
}

std::vector<std::string> tsa_preprocess_keys() {
  return {"iir_n", "touch", "baseline_seconds", "noise_sigmas", "min_threshold", "hold_off_frames"};
}

TsaPreprocessOptions tsa_preprocess_options(const Parameters& parameters) {
  TsaPreprocessOptions options;
  options.iir_window = parameters.integer("iir_n", options.iir_window);
  if (!is_power_of_two(options.iir_window))
    throw Error(parameters.where(),
                "iir_n=" + std::to_string(options.iir_window) + ": must be a power of two >= 1");
  options.touch = parameters.text("touch", options.touch);
  if (options.touch != "auto" && options.touch != "rising" && options.touch != "falling")
    throw Error(parameters.where(),
                "touch=" + options.touch + ": expected rising, falling or auto");
  ContactTriggerOptions& trigger = options.trigger;
  trigger.baseline_seconds = parameters.number("baseline_seconds", trigger.baseline_seconds);
  trigger.noise_sigmas = parameters.number("noise_sigmas", trigger.noise_sigmas);
  trigger.minimum_threshold = parameters.number("min_threshold", trigger.minimum_threshold);
  trigger.hold_off_frames = parameters.integer("hold_off_frames", trigger.hold_off_frames);
  if (!(trigger.baseline_seconds > 0.0))
    throw Error(parameters.where(), "baseline_seconds must be positive");
  if (trigger.noise_sigmas < 0.0)
    throw Error(parameters.where(), "noise_sigmas must not be negative");
  if (trigger.minimum_threshold < 0.0)
    throw Error(parameters.where(), "min_threshold must not be negative");
  if (trigger.hold_off_frames < 0)
    throw Error(parameters.where(), "hold_off_frames must not be negative");
  return options;
}

const Stream& tsa_stream(const Recording& recording) {
  const Stream* stream = recording.find_stream("skin");
  if (stream == nullptr && !recording.streams.empty()) stream = &recording.streams.front();
  if (stream == nullptr) throw Error(recording.id, "recording has no stream");
  if (!(stream->rate_hz > 0.0))
    throw Error(recording.id + " stream " + stream->name, "the frame rate must be positive");
  return *stream;
}

bool tsa_touch_rises(const Recording& recording, const std::string& touch) {
  if (touch == "rising") return true;
  if (touch == "falling") return false;
  const auto found = recording.metadata.find("front_end");
  if (found != recording.metadata.end()) {
    if (found->second.find("rising") != std::string::npos) return true;
    if (found->second.find("falling") != std::string::npos) return false;
  }
  return false;
}

Recording tsa_preprocess(const Recording& recording, const SkinLayout& layout,
                         const TsaPreprocessOptions& options) {
  const Stream& raw = tsa_stream(recording);
  const std::vector<TsaSheet> sheets = tsa_sheets(layout, raw);
  std::vector<std::vector<int>> groups;
  for (const TsaSheet& sheet : sheets) groups.push_back(sheet.columns);

  ContactTriggerOptions trigger = options.trigger;
  trigger.rate_hz = raw.rate_hz;
  trigger.rising = tsa_touch_rises(recording, options.touch);
  ContactTrigger contacts =
      contact_trigger(iir_average_columns(raw.samples, options.iir_window), groups, trigger);

  Recording result = recording;
  for (Stream& stream : result.streams) {
    if (stream.name != raw.name) continue;
    stream.samples = std::move(contacts.contact);
    stream.units.assign(stream.channels.size(), "counts above baseline");
    break;
  }
  result.metadata["preprocessing"] = "tsa: IIR average N=" + std::to_string(options.iir_window) +
                                     ", baseline over " + std::to_string(trigger.baseline_seconds) +
                                     " s, trigger " + std::to_string(trigger.noise_sigmas) +
                                     " sigma (min " + std::to_string(trigger.minimum_threshold) +
                                     " counts), touch " + (trigger.rising ? "rising" : "falling");
  return result;
}

}  // namespace tactile::dsp
