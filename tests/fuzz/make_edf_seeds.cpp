// Writes the `edf` fuzz target's seeds (tests/fuzz/corpus/edf/) with EDFlib, the fixtures of
// tests/support/edf_test_files.h and smaller files of the same kind, each under 20 kB:
//   build/bin/make_edf_seeds tests/fuzz/corpus/edf
#include <cstdio>
#include <filesystem>
#include <string>

#include "edf_test_files.h"

using namespace tactile::testing;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_edf_seeds FOLDER\n");
    return 2;
  }
  const std::filesystem::path folder = argv[1];
  std::filesystem::create_directories(folder);
  write_edf_test_file((folder / "plus-five-signals-two-rates.edf").string(), edf_test_plus_file());
  write_edf_test_file((folder / "bdf-plus-24-bit.bdf").string(), edf_test_bdf_file());

  EdfTestFile small;
  small.signals = {{"A", 8, -10.0, 10.0, -100, 100, "uV"}, {"B", 8, 0.0, 1.0, 0, 255, "mV"}};
  small.records = 2;
  small.annotations = {{0.25, 0.5, "Tap"}, {1.0, -1.0, "Hold"}};
  small.header_fields = false;
  write_edf_test_file((folder / "plus-two-signals-one-rate.edf").string(), small);

  EdfTestFile one = small;
  one.bdf = true;
  one.signals = {{"F", 4, -1.0, 1.0, -8388608, 8388607, "N"}};
  one.records = 3;
  one.record_seconds = 0.25;
  one.header_fields = true;
  write_edf_test_file((folder / "bdf-plus-one-signal.bdf").string(), one);
  return 0;
}
