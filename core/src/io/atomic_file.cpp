#include "tactile/io/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <filesystem>

#include "tactile/error.h"

namespace tactile {

namespace {

// A name beside `path` that no other call of this process uses and no file has now (one left
// by a crashed process of the same id is passed over). The process id keeps two programs
// writing one path apart. A folder that cannot be read (missing, no permission) gives the
// first name: the writer then fails with the reason.
std::string temporary_beside(const std::string& path) {
  static std::atomic<uint64_t> counter{0};
  while (true) {
    std::string temporary =
        path + ".tmp-" + std::to_string(getpid()) + "-" + std::to_string(counter++);
    struct stat status;
    if (lstat(temporary.c_str(), &status) != 0) return temporary;
  }
}

// fsync of a file or folder opened read-only; false with errno set on failure.
bool sync_path(const std::string& path, int flags) {
  const int descriptor = open(path.c_str(), O_RDONLY | O_CLOEXEC | flags);
  if (descriptor < 0) return false;
  const bool synced = fsync(descriptor) == 0;
  const int error = errno;
  close(descriptor);
  errno = error;
  return synced;
}

// The folder that holds `path` ("." for a bare file name).
std::string folder_of(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  return parent.empty() ? "." : parent.string();
}

}  // namespace

void write_file_atomically(const std::string& path, std::string_view text,
                           const std::string& what) {
  write_file_atomically(
      path,
      [&](const std::string& temporary) {
        std::FILE* file = std::fopen(temporary.c_str(), "wbx");
        if (file == nullptr) throw Error(path, system_error("cannot write the " + what));
        const bool written = std::fwrite(text.data(), 1, text.size(), file) == text.size();
        const int error = errno;
        if (std::fclose(file) != 0 || !written) {
          if (!written) errno = error;
          throw Error(path, system_error("cannot write the " + what));
        }
      },
      what);
}

void write_file_atomically(const std::string& path,
                           const std::function<void(const std::string& temporary_path)>& write,
                           const std::string& what) {
  const std::string temporary = temporary_beside(path);
  try {
    write(temporary);
    // On disk before the rename: otherwise a crash can leave the new name on empty blocks.
    if (!sync_path(temporary, 0)) throw Error(path, system_error("cannot write the " + what));
    if (std::rename(temporary.c_str(), path.c_str()) != 0)
      throw Error(path, system_error("cannot replace the " + what));
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
  // The rename is an entry of the folder: on disk only once the folder is. A file system that
  // cannot sync a folder (EINVAL) makes renames durable by itself.
  if (!sync_path(folder_of(path), O_DIRECTORY) && errno != EINVAL)
    throw Error(path, system_error("the " + what + " is written, but its folder cannot be synced"));
}

}  // namespace tactile
