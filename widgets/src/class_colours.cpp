#include "tactile/widgets/class_colours.h"

#include <algorithm>
#include <cmath>

namespace tactile {

namespace {

uint32_t packed(double r, double g, double b) {
  const auto byte = [](double value) {
    return static_cast<uint32_t>(std::lround(std::clamp(value, 0.0, 1.0) * 255.0));
  };
  return 0xFF000000u | byte(b) << 16 | byte(g) << 8 | byte(r);
}

// A fully saturated-enough colour of hue h (turns) at the palette's lightness.
uint32_t hue_colour(double hue) {
  const double saturation = 0.6, value = 0.85;
  const double sector = std::fmod(hue, 1.0) * 6.0;
  const double fraction = sector - std::floor(sector);
  const double p = value * (1 - saturation), q = value * (1 - saturation * fraction),
               t = value * (1 - saturation * (1 - fraction));
  switch (static_cast<int>(sector) % 6) {
    case 0:
      return packed(value, t, p);
    case 1:
      return packed(q, value, p);
    case 2:
      return packed(p, value, t);
    case 3:
      return packed(p, q, value);
    case 4:
      return packed(t, p, value);
    default:
      return packed(value, p, q);
  }
}

}  // namespace

uint32_t class_palette_colour(size_t index) {
  static const uint32_t kTableau[9] = {
      packed(31 / 255.0, 119 / 255.0, 180 / 255.0),  packed(255 / 255.0, 127 / 255.0, 14 / 255.0),
      packed(44 / 255.0, 160 / 255.0, 44 / 255.0),   packed(214 / 255.0, 39 / 255.0, 40 / 255.0),
      packed(148 / 255.0, 103 / 255.0, 189 / 255.0), packed(140 / 255.0, 86 / 255.0, 75 / 255.0),
      packed(227 / 255.0, 119 / 255.0, 194 / 255.0), packed(188 / 255.0, 189 / 255.0, 34 / 255.0),
      packed(23 / 255.0, 190 / 255.0, 207 / 255.0)};
  if (index < 9) return kTableau[index];
  // Golden-angle steps never come back to a hue they gave (it is irrational).
  constexpr double kGoldenTurn = 0.381966011250105;
  return hue_colour(0.07 + static_cast<double>(index - 9) * kGoldenTurn);
}

uint32_t distinct_palette_colour(size_t index) {
  // Greedy farthest-point picks in CIELAB from an sRGB grid (lightness 50-88, chroma 25 and
  // more: not the grey of "no region", not the white of a touch's ring).
  static const uint8_t kDistinct[][3] = {
      {34, 136, 204},  {0, 255, 0},     {255, 0, 0},     {255, 0, 255},  {204, 187, 102},
      {238, 102, 153}, {0, 238, 221},   {102, 102, 255}, {0, 153, 34},   {255, 153, 0},
      {187, 221, 0},   {238, 204, 255}, {187, 102, 68},  {85, 136, 102}, {238, 136, 255},
      {153, 238, 153}, {255, 0, 85},    {136, 221, 255}, {238, 0, 170},  {153, 102, 153},
      {255, 187, 170}, {0, 238, 102},   {153, 153, 255}, {221, 187, 0}};
  constexpr size_t kCount = std::size(kDistinct);
  if (index >= kCount) return class_palette_colour(index - kCount + 9);
  const uint8_t* rgb = kDistinct[index];
  return packed(rgb[0] / 255.0, rgb[1] / 255.0, rgb[2] / 255.0);
}

ClassColours::ClassColours(std::vector<std::string> neutral) : neutral_(std::move(neutral)) {}

void ClassColours::set_vocabulary(const std::vector<std::string>& vocabulary) {
  std::vector<std::string> order = vocabulary;
  for (const std::string& name : order_)
    if (std::find(order.begin(), order.end(), name) == order.end()) order.push_back(name);
  order_ = std::move(order);
}

uint32_t ClassColours::colour(const std::string& name, int alpha) {
  const uint32_t opacity = static_cast<uint32_t>(std::clamp(alpha, 0, 255)) << 24;
  if (name.empty() || std::find(neutral_.begin(), neutral_.end(), name) != neutral_.end())
    return (kNeutralClassColour & 0x00FFFFFFu) | opacity;
  auto found = std::find(order_.begin(), order_.end(), name);
  if (found == order_.end()) found = order_.insert(order_.end(), name);
  return (class_palette_colour(static_cast<size_t>(found - order_.begin())) & 0x00FFFFFFu) |
         opacity;
}

}  // namespace tactile
