// The one object that knows where this clone's assets are: TACTILE_ASSET_DIR, an absolute path,
// is defined on this file alone (core/CMakeLists.txt), so every other object is the same in two
// clones and a compiler cache can share it.
#include <cstdlib>
#include <string>

#include "tactile/layout/skin_layout.h"

namespace tactile {

std::string asset_dir() {
  const char* from_environment = std::getenv("TACTILE_ASSETS");
  if (from_environment != nullptr && from_environment[0] != '\0') return from_environment;
  return TACTILE_ASSET_DIR;
}

}  // namespace tactile
