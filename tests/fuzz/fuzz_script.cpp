// The workbench's script parser (docs/SCRIPTING.md): every line checked before anything runs.
#include <string>

#include "fuzz_support.h"
#include "script_parse.h"
#include "tactile/error.h"

using namespace tactile;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    for (const ScriptStep& step : parse_script(text, "fuzz.txt"))
      if (step.command == "key")
        for (const std::string& word : step.words) parse_chord(word);
  } catch (const Error&) {
  }
  return 0;
}
