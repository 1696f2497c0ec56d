#include "tactile/error.h"

#include <cerrno>
#include <cstring>

namespace tactile {

std::string system_error(const std::string& what) { return what + ": " + std::strerror(errno); }

}  // namespace tactile
