// The HDF5 recording reader on an in-memory file image: opening checks the format, metadata
// and every dataset's shape; then every stream is read whole, with its overview and time
// stamps, as the workbench and `tactile verify` would (read_all reads the same again).
#include "fuzz_support.h"
#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"

using namespace tactile;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const RecordingFile file = RecordingFile::from_image(fuzz::bytes_of(data, size), "fuzz.h5");
    for (const StreamInfo& stream : file.streams()) {
      file.read_timestamps(stream.name);
      file.read_overview(stream.name);
      if (stream.sample_count > 0) file.read(stream.name, 0, stream.sample_count);
    }
  } catch (const Error&) {
  }
  return 0;
}
