#pragma once
// How much a file can still grow: the free space of its file system (what an unprivileged
// writer may use) and, under a file-size limit (`ulimit -f`), what the limit leaves. A
// recorder asks it after each flush, warns while the room lasts less than some minutes at
// the current rate, and stops cleanly before it runs out.

#include <cstdint>
#include <string>

namespace tactile {

// Bytes `path` (a file, or the folder a file is about to be created in) can still grow by;
// -1 when the system cannot say.
int64_t room_to_grow(const std::string& path);

// "1.2 GB", "840 kB", "12 B": a byte count as a user reads it (powers of 1000).
std::string byte_text(int64_t bytes);

}  // namespace tactile
