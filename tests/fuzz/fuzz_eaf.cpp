// ELAN .eaf (elan_and_label_studio.h): `parse_eaf` on the bytes; what it accepts is written again
// by `labels_eaf` and must read back as as many labels (an export that its own reader refuses is a
// finding too).
#include <string>

#include "fuzz_support.h"
#include "tactile/error.h"
#include "tactile/labels/elan_and_label_studio.h"

using namespace tactile;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  InteropImport options;
  options.recording = "r";  // so that documents without a header reach the tiers
  try {
    const std::vector<Label> labels = parse_eaf(text, "fuzz.eaf", options);
    if (labels.empty()) return 0;
    const std::vector<Label> again = parse_eaf(labels_eaf(labels), "again.eaf");
    if (again.size() != labels.size()) __builtin_trap();
  } catch (const Error&) {
  }
  return 0;
}
