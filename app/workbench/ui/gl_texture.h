#pragma once
// The one place the workbench's panels call OpenGL: a video frame uploaded as a texture that
// ImGui draws. Both programs supply the GL (libGL in the window, OSMesa headless); these are
// OpenGL 1.1 calls that both export, so the panels' library links no GL of its own.

#include <cstdint>

namespace tactile {

// Uploads an RGBA image (top row first) into `texture` (0: a new one), returning the texture.
uint32_t upload_rgba_texture(uint32_t texture, int width, int height, const uint8_t* rgba,
                             bool same_size);
void delete_texture(uint32_t texture);

}  // namespace tactile
