#pragma once
// PNGs written by the workbench, read back for tests that look at pixels.

#include <stb_image.h>

#include <cstdlib>
#include <memory>
#include <set>
#include <string>

namespace tactile {

struct Png {
  int width = 0, height = 0;
  std::unique_ptr<unsigned char, void (*)(void*)> pixels{nullptr, stbi_image_free};
  const unsigned char* at(int x, int y) const {
    return pixels.get() + (static_cast<size_t>(y) * width + x) * 4;
  }
};

inline Png read_png(const std::string& path) {
  Png png;
  int channels = 0;
  png.pixels.reset(stbi_load(path.c_str(), &png.width, &png.height, &channels, 4));
  return png;
}

// Pixels close to the top of viridis (a fully touched taxel) anywhere in the image.
inline int count_viridis_top(const Png& png) {
  int count = 0;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x) {
      const unsigned char* p = png.at(x, y);
      count += std::abs(p[0] - 253) < 8 && std::abs(p[1] - 231) < 8 && std::abs(p[2] - 37) < 12;
    }
  return count;
}

// Distinct colours of an image region (every second pixel; the whole image by default): a view
// that drew nothing has two or three.
inline size_t colours_in(const Png& png, int x0 = 0, int y0 = 0, int x1 = -1, int y1 = -1) {
  if (x1 < 0) x1 = png.width;
  if (y1 < 0) y1 = png.height;
  std::set<uint32_t> colours;
  for (int y = y0; y < y1; y += 2)
    for (int x = x0; x < x1; x += 2) {
      const unsigned char* p = png.at(x, y);
      colours.insert(p[0] << 16 | p[1] << 8 | p[2]);
    }
  return colours.size();
}

}  // namespace tactile
