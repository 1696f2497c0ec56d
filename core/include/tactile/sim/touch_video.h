#pragma once
// A camera's view of a simulated session, for the demo workspace, the tests and the video sync
// benchmark (docs/VIDEO.md): the skin's map seen from above, and a hand that reaches the touched
// region at each labelled touch (stroking moves along it, patting and slapping bob), with some
// motion that is not touch (a person swaying at the edge of the picture) and sensor noise. Its
// motion follows the touches, as a real camera's does, so the sync's proposal can be tested
// against a known offset.

#include <cstdint>
#include <string>
#include <vector>

#include "tactile/labelstore/label.h"
#include "tactile/layout/skin_layout.h"

namespace tactile {

struct TouchVideoOptions {
  int width = 320;  // even
  int height = 240;
  double rate = 30.0;     // frames per second
  double offset = 0.0;    // the recording time of the video's first frame
  double duration = 0.0;  // seconds of video
  double sway = 1.0;      // how much the person at the edge moves (0: not at all)
  double noise = 3.0;     // grey levels of sensor noise per pixel
  uint64_t seed = 1;
  std::string codec;  // VideoWriterOptions::codec ("": by the file's extension)
};

// Writes the video of `touches` (recording times) on `layout` to `path` (the container by its
// extension). Throws tactile::Error naming the path.
void write_touch_video(const std::string& path, const SkinLayout& layout,
                       const std::vector<Label>& touches, const TouchVideoOptions& options);

}  // namespace tactile
