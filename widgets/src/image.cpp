#include "tactile/widgets/image.h"

#include <stb_image_write.h>

#include <algorithm>

#include "tactile/error.h"
#include "tactile/io/atomic_file.h"

namespace tactile {

Image::Rgba Image::at(int x, int y) const {
  const size_t offset = (static_cast<size_t>(y) * width + x) * 4;
  return {rgba[offset], rgba[offset + 1], rgba[offset + 2], rgba[offset + 3]};
}

void Image::flip_vertically() {
  const size_t row_bytes = static_cast<size_t>(width) * 4;
  for (int y = 0; y < height / 2; ++y)
    std::swap_ranges(rgba.begin() + y * row_bytes, rgba.begin() + (y + 1) * row_bytes,
                     rgba.begin() + (height - 1 - y) * row_bytes);
}

Image Image::crop(int x, int y, int crop_width, int crop_height) const {
  const int x0 = std::clamp(x, 0, width), y0 = std::clamp(y, 0, height);
  const int x1 = std::clamp(x + crop_width, x0, width),
            y1 = std::clamp(y + crop_height, y0, height);
  Image part;
  part.width = x1 - x0;
  part.height = y1 - y0;
  part.rgba.resize(static_cast<size_t>(part.width) * part.height * 4);
  for (int row = 0; row < part.height; ++row)
    std::copy_n(rgba.begin() + ((static_cast<size_t>(y0 + row) * width + x0) * 4),
                static_cast<size_t>(part.width) * 4,
                part.rgba.begin() + static_cast<size_t>(row) * part.width * 4);
  return part;
}

void write_png(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0) throw Error(path, "cannot write an empty image");
  write_file_atomically(
      path,
      [&](const std::string& temporary) {
        if (!stbi_write_png(temporary.c_str(), image.width, image.height, 4, image.rgba.data(),
                            image.width * 4))
          throw Error(path, "cannot write PNG (is the directory there and writable?)");
      },
      "PNG");
}

}  // namespace tactile
