#pragma once
// Perceptual colour maps for values in [0, 1].

#include <cstdint>

namespace tactile {

struct Colour {
  uint8_t r = 0, g = 0, b = 0, a = 255;
};

// Viridis (perceptually uniform, colour-blind safe); t is clamped to [0, 1], NaN -> grey.
Colour viridis(float t);
// Packs a colour the way ImGui's IM_COL32 does.
uint32_t pack_abgr(Colour colour);

}  // namespace tactile
