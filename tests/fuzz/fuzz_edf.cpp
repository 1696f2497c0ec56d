// The EDF+/BDF+ reader (import_edf: the header checks, then EDFlib) on a file of the process
// holding the input (EDFlib reads a path). The layout is a strip of as many channels as the
// header names ordinary signals, so a well-formed input goes on to the samples and the
// annotations instead of stopping at the channel count; annotations without a duration are
// given one.
#include <string>

#include "fuzz_support.h"
#include "tactile/error.h"
#include "tactile/formats/edf_files.h"

using namespace tactile;

namespace {

// The ordinary signals the header names (its signal count less the annotation signals), 1 to 64.
int edf_fuzz_signal_count(const uint8_t* data, size_t size) {
  if (size < 256) return 1;
  int declared = 0;
  for (size_t k = 252; k < 256; ++k)
    if (data[k] >= '0' && data[k] <= '9') declared = declared * 10 + (data[k] - '0');
  int ordinary = 0;
  for (int signal = 0; signal < declared && 256 + (signal + 1) * 16 <= static_cast<int>(size);
       ++signal) {
    const std::string label(reinterpret_cast<const char*>(data) + 256 + signal * 16, 16);
    if (label.rfind("EDF Annotations", 0) != 0 && label.rfind("BDF Annotations", 0) != 0)
      ++ordinary;
  }
  return ordinary < 1 ? 1 : ordinary > 64 ? 64 : ordinary;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = fuzz::write_input(fuzz::bytes_of(data, size), ".edf");
  const SkinLayout layout =
      load_layout("strip:" + std::to_string(edf_fuzz_signal_count(data, size)));
  EdfImportOptions options;
  options.annotation_seconds = 0.5;
  try {
    import_edf(path, layout, options);
  } catch (const Error&) {
  }
  return 0;
}
