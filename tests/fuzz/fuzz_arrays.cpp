// Foreign array formats (docs/IMPORT.md): a .npy file's bytes, a .npz archive (every array
// in it), or JSON frames (the top-level array or the one under key "frames"); each array
// found is then made into a recording of a small generic layout, as `tactile import` does.
// The first byte picks the format and the shape's reading.
#include "fuzz_support.h"
#include "tactile/error.h"
#include "tactile/formats/array_files.h"
#include "tactile/layout/skin_layout.h"

using namespace tactile;

namespace {

void to_recording(const ImportedArray& array, uint8_t mode) {
  static const SkinLayout grid = make_grid_layout(2, 2);
  static const SkinLayout strip = make_strip_layout(4);
  ArrayRecordingOptions options;
  options.rate_hz = 20.0;
  options.captures = (mode & 0x10) != 0;
  if (array.text) return;
  recording_from_array(array, mode & 0x20 ? grid : strip, options, "fuzz");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const uint8_t mode = data[0];
  const auto rest = fuzz::bytes_of(data + 1, size - 1);
  try {
    switch (mode % 3) {
      case 0:
        to_recording(parse_npy(rest, "fuzz.npy"), mode);
        break;
      case 1: {
        const std::string path = fuzz::write_input(rest, ".npz");
        for (const std::string& name : npz_names(path)) to_recording(read_npz(path, name), mode);
        break;
      }
      default:
        to_recording(read_json_array(fuzz::write_input(rest, ".json"), mode & 0x40 ? "frames" : ""),
                     mode);
        break;
    }
  } catch (const Error&) {
  }
  return 0;
}
