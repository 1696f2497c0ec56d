// MATLAB .mat files (formats/mat_files.h): the input is written to a file of this process (libmatio
// reads paths), every variable and struct field is listed, and each is read as `tactile import`
// would read it (numbers in C order, or names), the numeric ones then made into a recording of a
// small generic layout. Refusals are tactile::Error; libmatio must never be handed a structure
// it would crash, overread or allocate without bound on (mat_structure.cpp checks it first).
#include "fuzz_support.h"
#include "tactile/error.h"
#include "tactile/formats/mat_files.h"
#include "tactile/layout/skin_layout.h"

using namespace tactile;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const SkinLayout strip = make_strip_layout(4);
  const std::string path = fuzz::write_input(fuzz::bytes_of(data, size), ".mat");
  try {
    int read = 0;
    for (const MatVariable& variable : mat_variables(path)) {
      if (++read > 16) break;
      try {
        const ImportedArray array = read_mat_variable(path, variable.name);
        if (array.text) continue;
        ArrayRecordingOptions options;
        options.rate_hz = 20.0;
        recording_from_array(array, strip, options, "fuzz");
      } catch (const Error&) {
      }
    }
  } catch (const Error&) {
  }
  return 0;
}
