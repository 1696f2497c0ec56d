#include "tactile/io/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <fstream>

#include "tactile/error.h"

namespace tactile {

void write_file_atomically(const std::string& path, const std::string& text, const std::string& what) {
  static std::atomic<int> counter{0};
  const std::string temporary =
      path + ".tmp-" + std::to_string(getpid()) + "-" + std::to_string(counter++);
  bool written = false;
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (out) {
      out.write(text.data(), static_cast<std::streamsize>(text.size()));
      out.flush();
      written = static_cast<bool>(out);
    }
  }
  if (!written) {
    std::remove(temporary.c_str());
    throw Error(path, "cannot write the " + what);
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const std::string message = system_error("cannot replace the " + what);
    std::remove(temporary.c_str());
    throw Error(path, message);
  }
}

}  // namespace tactile
