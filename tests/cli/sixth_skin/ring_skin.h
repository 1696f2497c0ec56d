#pragma once
// A sixth skin, brought by this folder alone: a ring of 12 pressure taxels (its layout), a
// small simulator of two touches (a press in one place, a swipe around the ring) and a
// feature pipeline that tells them apart. register_ring_skin() adds all three to the
// program's tables; nothing outside this folder names the skin.

#include <string>

namespace tactile::test {

inline constexpr const char* kRingSkin = "ring";

// The layout file's text (also written beside the recordings for the workbench program,
// which finds it through TACTILE_LAYOUT_PATH).
std::string ring_layout_json();

// Registers the pipeline "ring_motion" and the skin "ring" (idempotent).
void register_ring_skin();

}  // namespace tactile::test
