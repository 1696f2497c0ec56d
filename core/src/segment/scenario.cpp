#include "tactile/segment/scenario.h"

#include <cmath>
#include <cstdio>

#include "tactile/error.h"
#include "tactile/text.h"

namespace tactile {

namespace {

const Stream& required_stream(const Recording& recording, const std::string& name,
                              const std::string& why) {
  const Stream* stream = recording.find_stream(name);
  if (stream == nullptr) throw Error(recording.id + " stream " + name, "missing: " + why);
  return *stream;
}

struct StageCommand {
  double time = 0.0;
  int64_t stage = 0;
};

// The commands in recording order, validated: finite whole stages within the layout's
// classes, time stamps that never go back.
std::vector<StageCommand> read_commands(const Recording& recording, const Stream& commands,
                                        const SkinLayout& layout) {
  if (commands.channel_count() < 1)
    throw Error(recording.id + " stream " + commands.name, "has no channel (expected \"stage\")");
  int channel = 0;
  for (size_t column = 0; column < commands.channels.size(); ++column)
    if (commands.channels[column] == "stage") channel = static_cast<int>(column);
  const int64_t classes = static_cast<int64_t>(layout.classes.size());
  std::vector<StageCommand> stages;
  for (int64_t k = 0; k < commands.sample_count(); ++k) {
    const std::string where =
        recording.id + " stream " + commands.name + " sample " + std::to_string(k);
    const double value = commands.samples(k, channel);
    const double time = commands.time_of(k);
    if (!std::isfinite(value) || value != std::floor(value) || value < 0 ||
        value >= static_cast<double>(classes))
      throw Error(where, "stage " + significant_text(value, 9) + " is not a stage of layout " +
                             layout.id + " (0.." + std::to_string(classes - 1) + ")");
    if (!std::isfinite(time)) throw Error(where, "time stamp is not finite");
    if (!stages.empty() && time < stages.back().time)
      throw Error(where, "time stamp goes back (" + significant_text(time, 9) + " s after " +
                             significant_text(stages.back().time, 9) + " s)");
    stages.push_back({time, static_cast<int64_t>(value)});
  }
  return stages;
}

}  // namespace

std::vector<Label> segment_scenario(const Recording& recording, const SkinLayout& layout,
                                    const Parameters& parameters) {
  parameters.expect_only({"commands", "stream"});
  const Stream& commands =
      required_stream(recording, parameters.text("commands", "commands"),
                      "the scenario segmenter needs the stage command time stamps");
  const Stream& skin = required_stream(recording, parameters.text("stream", "skin"),
                                       "the scenario segmenter needs the skin stream");
  const std::vector<StageCommand> stages = read_commands(recording, commands, layout);
  const double end = skin.sample_count() > 0 ? skin.time_of(0) + skin.duration() : 0.0;

  std::vector<Label> labels;
  for (size_t k = 0; k < stages.size();) {
    // A repeated command of the same stage continues it; a missing stage simply leaves
    // its span to the stage before (spec §4.1).
    size_t next = k + 1;
    while (next < stages.size() && stages[next].stage == stages[k].stage) ++next;
    Label label;
    label.recording = recording.id;
    label.t0 = stages[k].time;
    label.t1 = next < stages.size() ? stages[next].time : end;
    label.region = "all";
    label.class_name = layout.classes[size_t(stages[k].stage)];
    label.annotator = "segmenter:scenario";
    label.source = LabelSource::kSegmenter;
    const auto [first, last] = sample_range(skin, label.t0, label.t1);
    if (last - first >= 2) labels.push_back(std::move(label));
    k = next;
  }
  return labels;
}

}  // namespace tactile
