#include "osmesa_renderer.h"

#include <GL/osmesa.h>
#include <imgui.h>

#include <cstring>

#include "imgui_impl_opengl3.h"
#include "tactile/error.h"

namespace tactile {

OffscreenRenderer::OffscreenRenderer(int width, int height)
    : width_(width), height_(height), buffer_(static_cast<size_t>(width) * height * 4) {
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            0,
                            OSMESA_PROFILE,
                            OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION,
                            3,
                            OSMESA_CONTEXT_MINOR_VERSION,
                            3,
                            0};
  context_ = OSMesaCreateContextAttribs(attributes, nullptr);
  if (!context_) throw Error("OSMesa", "cannot create an OpenGL 3.3 core context");
  if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, width_, height_)) {
    OSMesaDestroyContext(context_);
    throw Error("OSMesa", "cannot make the context current");
  }
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  io.LogFilename = nullptr;
  ImGui::StyleColorsDark();
  if (!ImGui_ImplOpenGL3_Init("#version 330")) {
    ImGui::DestroyContext();
    OSMesaDestroyContext(context_);
    throw Error("OSMesa", "cannot initialise the ImGui OpenGL3 backend");
  }
}

OffscreenRenderer::~OffscreenRenderer() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext();
  OSMesaDestroyContext(context_);
}

void OffscreenRenderer::new_frame(float seconds) {
  prepare_frame(seconds);
  ImGui::NewFrame();
}

void OffscreenRenderer::prepare_frame(float seconds) {
  ImGui_ImplOpenGL3_NewFrame();
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(width_), static_cast<float>(height_));
  io.DisplayFramebufferScale = ImVec2(1.0f, 1.0f);
  io.DeltaTime = seconds > 0 ? seconds : 1.0f / 60.0f;
}

Image OffscreenRenderer::render(float clear_r, float clear_g, float clear_b) {
  ImGui::Render();
  glViewport(0, 0, width_, height_);
  glClearColor(clear_r, clear_g, clear_b, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  glFinish();
  // OSMesa's buffer has its first row at the bottom; images here are top row first.
  Image image;
  image.width = width_;
  image.height = height_;
  image.rgba.resize(buffer_.size());
  const size_t row_bytes = static_cast<size_t>(width_) * 4;
  for (int y = 0; y < height_; ++y)
    std::memcpy(image.rgba.data() + y * row_bytes, buffer_.data() + (height_ - 1 - y) * row_bytes,
                row_bytes);
  return image;
}

}  // namespace tactile
