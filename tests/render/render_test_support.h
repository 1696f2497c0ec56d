#pragma once
// Helpers shared by the render tests: a borderless full-size window to draw into,
// colour comparison, and where the PNGs of what was rendered go.

#include <imgui.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "osmesa_renderer.h"
#include "tactile/widgets/colormap.h"

namespace tactile::testing {

// Begins a window covering the whole frame, without padding or decoration, so a
// widget drawn at its cursor starts at pixel (0, 0).
inline void begin_canvas(const OffscreenRenderer& renderer) {
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(
      ImVec2(static_cast<float>(renderer.width()), static_cast<float>(renderer.height())));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0, 0));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowBorderSize, 0.0f);
  ImGui::Begin("canvas", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBackground);
}

inline void end_canvas() {
  ImGui::End();
  ImGui::PopStyleVar(2);
}

inline bool close_to(Image::Rgba pixel, Colour expected, int tolerance) {
  return std::abs(pixel.r - expected.r) <= tolerance &&
         std::abs(pixel.g - expected.g) <= tolerance && std::abs(pixel.b - expected.b) <= tolerance;
}

inline bool close_to_packed(Image::Rgba pixel, uint32_t abgr, int tolerance) {
  const Colour expected{static_cast<uint8_t>(abgr & 0xff), static_cast<uint8_t>((abgr >> 8) & 0xff),
                        static_cast<uint8_t>((abgr >> 16) & 0xff), 255};
  return close_to(pixel, expected, tolerance);
}

// /tmp/widgets/<name>.png, for a person to look at.
inline std::string png_path(const std::string& name) {
  const std::filesystem::path directory = "/tmp/widgets";
  std::filesystem::create_directories(directory);
  return (directory / (name + ".png")).string();
}

}  // namespace tactile::testing
