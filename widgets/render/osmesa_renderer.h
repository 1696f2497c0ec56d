#pragma once
// Off-screen Dear ImGui rendering through OSMesa (software OpenGL 3.3 core, no X).
// Used by the render tests, the headless workbench and `--screenshot --headless`.

#include <cstdint>
#include <string>
#include <vector>

#include "tactile/widgets/image.h"

struct osmesa_context;

namespace tactile {

class OffscreenRenderer {
 public:
  // Creates the OSMesa context, an ImGui context (no .ini file) and the backend.
  // Throws tactile::Error when OSMesa cannot give a 3.3 core context.
  OffscreenRenderer(int width, int height);
  ~OffscreenRenderer();
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  // Starts an ImGui frame of the renderer's size; `seconds` is the frame's delta time.
  void new_frame(float seconds = 1.0f / 60.0f);
  // The backend's part of new_frame without ImGui::NewFrame, so that input (a script)
  // can be set in between.
  void prepare_frame(float seconds = 1.0f / 60.0f);
  // Ends the frame, draws it and reads the pixels back.
  Image render(float clear_r = 0.09f, float clear_g = 0.09f, float clear_b = 0.1f);

  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_;
  int height_;
  osmesa_context* context_ = nullptr;
  std::vector<uint8_t> buffer_;
};

}  // namespace tactile
