#pragma once
// Writing a whole file so that it is either the old one or the new one: the text goes to a
// temporary file beside it (unique per process and call), which is then renamed over the
// path. A failed write removes the temporary and leaves the path as it was.

#include <string>

namespace tactile {

// Throws tactile::Error(path, "cannot write the WHAT ...") on failure.
void write_file_atomically(const std::string& path, const std::string& text,
                           const std::string& what = "file");

}  // namespace tactile
