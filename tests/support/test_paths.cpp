#include "test_paths.h"

namespace tactile::test {

std::string test_data_dir() { return TACTILE_TEST_DATA_DIR; }
std::string bin_dir() { return TACTILE_BIN_DIR; }
std::string asset_dir() { return TACTILE_ASSET_DIR; }

}  // namespace tactile::test
