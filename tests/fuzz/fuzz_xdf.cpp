// XDF recordings (docs/IMPORT.md, "XDF"): scan_xdf walks every chunk; then each numeric
// stream with a nominal rate is imported as `tactile import` would (libxdf reading the
// checked copy, resampling, the default markers stream's labels) into a strip layout of its
// channel count.
#include <cstdlib>

#include "fuzz_support.h"
#include "tactile/error.h"
#include "tactile/formats/xdf_files.h"
#include "tactile/layout/skin_layout.h"

using namespace tactile;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // The copy libxdf reads goes where the input is: a tmpfs when there is one.
  static const bool in_memory = [] {
    if (std::filesystem::is_directory("/dev/shm")) setenv("TMPDIR", "/dev/shm", 1);
    return true;
  }();
  (void)in_memory;
  const std::string path = fuzz::write_input(fuzz::bytes_of(data, size), ".xdf");
  try {
    const std::vector<XdfStreamInfo> streams = scan_xdf(path);
    for (const XdfStreamInfo& stream : streams) {
      if (stream.format == "string" || !(stream.rate_hz > 0.0) || stream.channels > 64) continue;
      XdfImportOptions options;
      options.stream = stream.name;
      try {
        import_xdf(path, make_strip_layout(stream.channels), options);
      } catch (const Error&) {
      }
    }
  } catch (const Error&) {
  }
  return 0;
}
