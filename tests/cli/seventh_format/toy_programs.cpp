// The seventh format in the programs this folder builds (CMakeLists.txt): `tactile` and the
// headless workbench with the toy importer registered at start-up, as a lab's own build of the
// workbench would add its format.
#include "toy_format.h"

namespace {

const bool kToyRegistered = (tactile::test::register_toy_format(), true);

}  // namespace
