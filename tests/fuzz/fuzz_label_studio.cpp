// Label Studio's JSON export (elan_and_label_studio.h): `is_label_studio_json` and
// `parse_label_studio` on the bytes; what it accepts is written again by `labels_label_studio`
// and must read back as as many labels.
#include <string>

#include "fuzz_support.h"
#include "tactile/error.h"
#include "tactile/labels/elan_and_label_studio.h"

using namespace tactile;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  (void)is_label_studio_json(text);
  InteropImport options;
  if (size > 0 && (data[0] & 1)) options.annotators = {{"1", "ground-truth"}, {"2", "model:m"}};
  try {
    const std::vector<Label> labels = parse_label_studio(text, "fuzz.json", options);
    if (labels.empty()) return 0;
    const std::vector<Label> again = parse_label_studio(labels_label_studio(labels), "again.json");
    if (again.size() != labels.size()) __builtin_trap();
  } catch (const Error&) {
  }
  return 0;
}
