// Room for a file to grow: statvfs and the file-size limit.
#include "tactile/io/disk_room.h"

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/statvfs.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

namespace tactile {

int64_t room_to_grow(const std::string& path) {
  struct stat file {};
  const bool exists = ::stat(path.c_str(), &file) == 0;
  const std::string folder =
      exists && S_ISDIR(file.st_mode) ? path : std::filesystem::path(path).parent_path().string();
  struct statvfs disk {};
  if (::statvfs(folder.empty() ? "." : folder.c_str(), &disk) != 0) return -1;
  int64_t room = static_cast<int64_t>(disk.f_bavail) * static_cast<int64_t>(disk.f_frsize);
  struct rlimit limit {};
  if (::getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    const int64_t size = exists && S_ISREG(file.st_mode) ? static_cast<int64_t>(file.st_size) : 0;
    room = std::min(room, std::max<int64_t>(0, static_cast<int64_t>(limit.rlim_cur) - size));
  }
  return room;
}

std::string byte_text(int64_t bytes) {
  static const char* const kUnits[] = {"B", "kB", "MB", "GB", "TB"};
  double value = static_cast<double>(bytes);
  int unit = 0;
  while (value >= 1000.0 && unit < 4) {
    value /= 1000.0;
    ++unit;
  }
  char text[32];
  std::snprintf(text, sizeof(text), unit == 0 ? "%.0f %s" : "%.3g %s", value, kUnits[unit]);
  return text;
}

}  // namespace tactile
