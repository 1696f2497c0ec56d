// A deliberate finding for each sanitizer of the sanitizer build: proof, run as a test, that
// the build's ASan and UBSan are on and stop the program at a finding (tests/CMakeLists.txt).
// `sanitizer_canary address` copies one element from past a heap array; `sanitizer_canary
// undefined` overflows a signed int. Both take their operands from the command line, so that no
// compiler can see the fault and fold it away. After the fault the program prints "not stopped".
#include <cstdio>
#include <cstdlib>
#include <cstring>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: sanitizer_canary address|undefined\n");
    return 2;
  }
  volatile int sink = 0;
  if (std::strcmp(argv[1], "address") == 0) {
    const int size = 3 + static_cast<int>(std::strlen(argv[1])) % 1;  // 3, unknown to the compiler
    int* values = new int[static_cast<size_t>(size)]();
    int read = 0;
    std::memcpy(&read, values + size, sizeof read);  // one past the end
    sink = read;
    delete[] values;
  } else if (std::strcmp(argv[1], "undefined") == 0) {
    int large = 2147483600 + static_cast<int>(std::strlen(argv[1])) % 1;
    large += 100;  // signed overflow
    sink = large;
  } else {
    std::fprintf(stderr, "sanitizer_canary: no fault '%s' (address, undefined)\n", argv[1]);
    return 2;
  }
  std::printf("not stopped (%d)\n", sink);
  return 0;
}
