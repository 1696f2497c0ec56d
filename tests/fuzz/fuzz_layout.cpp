// The layout JSON loader and its validation (assets/layouts/*.json, or a user's own layout).
#include <nlohmann/json.hpp>
#include <string>

#include "fuzz_support.h"
#include "tactile/error.h"
#include "tactile/layout/skin_layout.h"

using namespace tactile;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const SkinLayout layout = parse_layout_json(text, "fuzz.json");
    validate_layout(layout, "fuzz.json");
    for (const Taxel& taxel : layout.taxels) taxel_outline(taxel);
  } catch (const Error&) {
  }
  return 0;
}
