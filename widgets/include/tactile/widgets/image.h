#pragma once
// An RGBA image read back from a renderer, and PNG output.

#include <cstdint>
#include <string>
#include <vector>

namespace tactile {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;  // top row first

  struct Rgba {
    uint8_t r, g, b, a;
  };
  // Colour of pixel (x, y), y counted from the top.
  Rgba at(int x, int y) const;
  // Flips rows in place: OpenGL reads the bottom row first.
  void flip_vertically();
  // The part [x, x + width) x [y, y + height), clipped to the image.
  Image crop(int x, int y, int crop_width, int crop_height) const;
};

// Writes an RGBA image to PNG; throws tactile::Error naming the path on failure.
void write_png(const std::string& path, const Image& image);

}  // namespace tactile
