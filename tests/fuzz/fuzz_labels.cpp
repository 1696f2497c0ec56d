// Label import, CSV (RFC 4180 with quoted fields) and JSON ({"labels": [...]}): the first
// byte picks the format.
#include "fuzz_support.h"
#include "tactile/error.h"
#include "tactile/labelstore/label_csv_json.h"

using namespace tactile;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  try {
    const std::string path =
        fuzz::write_input(fuzz::bytes_of(data + 1, size - 1), data[0] & 1 ? ".json" : ".csv");
    if (data[0] & 1)
      read_labels_json(path);
    else
      read_labels_csv(path);
  } catch (const Error&) {
  }
  return 0;
}
