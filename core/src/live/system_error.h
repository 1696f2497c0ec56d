#pragma once
// The operating system's reason for a failed call, for the live inputs' messages. Private to
// core/src/live.

#include <cerrno>
#include <cstring>
#include <string>

namespace tactile {

// "WHAT: REASON", with the reason errno names now ("cannot bind: Address already in use").
inline std::string system_error(const std::string& what) {
  return what + ": " + std::strerror(errno);
}

}  // namespace tactile
