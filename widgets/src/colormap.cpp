#include "tactile/widgets/colormap.h"

#include <algorithm>
#include <cmath>

namespace tactile {

namespace {
// Viridis sampled at nine evenly spaced points; linear interpolation between them
// stays within a few levels of the full 256-entry table.
constexpr uint8_t kViridis[9][3] = {{68, 1, 84},    {72, 40, 120},  {62, 73, 137},
                                    {49, 104, 142}, {38, 130, 142}, {31, 158, 137},
                                    {53, 183, 121}, {110, 206, 88}, {253, 231, 37}};
}  // namespace

Colour viridis(float t) {
  if (std::isnan(t)) return {128, 128, 128, 255};
  const float position = std::clamp(t, 0.0f, 1.0f) * 8.0f;
  const int low = std::min(7, static_cast<int>(position));
  const float fraction = position - static_cast<float>(low);
  Colour colour;
  uint8_t* channels[3] = {&colour.r, &colour.g, &colour.b};
  for (int k = 0; k < 3; ++k) {
    const float value = kViridis[low][k] + fraction * (kViridis[low + 1][k] - kViridis[low][k]);
    *channels[k] = static_cast<uint8_t>(std::lround(value));
  }
  return colour;
}

uint32_t pack_abgr(Colour colour) {
  return (static_cast<uint32_t>(colour.a) << 24) | (static_cast<uint32_t>(colour.b) << 16) |
         (static_cast<uint32_t>(colour.g) << 8) | colour.r;
}

}  // namespace tactile
