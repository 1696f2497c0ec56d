#pragma once
// Where this clone's test data, built programs and assets are. The absolute paths are compiled
// into tests/support/test_paths.cpp alone, so that no other test object depends on the folder
// of the clone and a compiler cache can share them between clones (README, "Tests and CI").

#include <string>

namespace tactile::test {

std::string test_data_dir();  // tests/data
std::string bin_dir();        // the build's bin/, where tactile and the workbench are
std::string asset_dir();      // assets/, as the build configured it

}  // namespace tactile::test
