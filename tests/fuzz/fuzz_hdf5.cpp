// HDF5 files, read two ways. The recording reader on an in-memory file image: opening checks
// the format, metadata and every dataset's shape; then every stream is read whole, with its
// overview and time stamps, as the workbench and `tactile verify` would. And the import of
// another program's .h5 (formats/array_files.h): the input written to a file of this process,
// its structure walked and its datasets listed (hdf5_structure.cpp), each (16 at most) read as
// `tactile import FILE.h5 --dataset PATH` reads it.
#include "fuzz_support.h"
#include "tactile/error.h"
#include "tactile/formats/array_files.h"
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
  const std::string path = fuzz::write_input(fuzz::bytes_of(data, size), ".h5");
  try {
    int read = 0;
    for (const Hdf5Dataset& dataset : hdf5_datasets(path)) {
      if (++read > 16) break;
      try {
        read_hdf5_dataset(path, dataset.path);
      } catch (const Error&) {
      }
    }
  } catch (const Error&) {
  }
  return 0;
}
