#pragma once
// A seventh recording format, brought by this folder alone: a text file whose first line is
// "toy RATE" and whose every other line holds one frame (a number per channel) and optionally
// its class. Its options: --gain (each value multiplied), --skip (frames left out at the
// start), --no-classes (the classes ignored).

#include <string>

namespace tactile::test {

inline constexpr const char* kToyFormat = "Toy text";

// Adds the toy importer to the program's list (tactile/formats/importer.h).
void register_toy_format();

// A toy file of `frames` frames of `channels` channels at 20 Hz: frame k holds k + channel,
// classes "tap" for the second half, none before.
std::string toy_file_text(int frames, int channels);

}  // namespace tactile::test
