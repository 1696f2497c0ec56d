#pragma once
// Scenario segmenter (spec §4.1, Robovie paper 003): the robot's stage commands label the
// recording. A "commands" stream holds one sample per stage start command, at irregular
// time stamps, whose value is the stage index into the layout's classes (0 = "Hello.").

#include <vector>

#include "tactile/io/recording.h"
#include "tactile/labelstore/label.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"

namespace tactile {

// One label per stage: [command time, next command time), the last one up to the end of
// the skin stream; class = layout.classes[stage]. A missing command merges its span into
// the previous stage's; a command repeating the current stage continues it; a span with
// fewer than 2 skin samples is dropped. Parameters: commands=<stream> (default
// "commands"), stream=<skin stream> (default "skin"). Throws tactile::Error naming the
// stream and sample for a missing stream, a stage outside the layout's classes or time
// stamps that go back.
std::vector<Label> segment_scenario(const Recording& recording, const SkinLayout& layout,
                                    const Parameters& parameters);

}  // namespace tactile
