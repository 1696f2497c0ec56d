#pragma once
// Writing a whole file so that it is either the old one or the new one, also after a crash or
// a power cut: the content goes to a temporary file beside the path (unique per process and
// call), which is synced to disk, renamed over the path, and the folder synced so that the
// rename itself is on disk. A failed write removes the temporary and leaves the path as it was.

#include <functional>
#include <string>
#include <string_view>

namespace tactile {

// Writes `text`. Throws tactile::Error(path, "cannot write the WHAT: REASON") (or "cannot
// replace the WHAT: ...", "cannot sync ...") on failure.
void write_file_atomically(const std::string& path, std::string_view text,
                           const std::string& what = "file");

// For writers that make the file themselves (a library such as HDF5, or a stream written in
// blocks): `write(temporary_path)` creates the file at the path it is given, which does not
// exist yet, and throws on failure. Whatever it throws is passed on after the temporary is
// removed; after it returns, the file is synced and renamed as above.
void write_file_atomically(const std::string& path,
                           const std::function<void(const std::string& temporary_path)>& write,
                           const std::string& what = "file");

}  // namespace tactile
