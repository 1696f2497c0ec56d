#pragma once
// Mending a recording that a failed write left behind (a full disk, a pulled stick while
// recording): `tactile repair FILE`. What the samples say is rebuilt (the min/max overview,
// the sample count); what cannot be read is named as lost. The repaired file is written beside
// the original, verified, and only then takes its name; the original is kept beside it.

#include <string>
#include <vector>

namespace tactile {

struct RepairReport {
  bool repaired = false;             // false: the file verified whole, nothing was done
  std::vector<std::string> rebuilt;  // one line per thing rebuilt from the samples
  std::vector<std::string> lost;     // one line per stretch that could not be kept
  std::string kept_original;         // where the damaged original now is ("" if untouched)
};

// Verifies `path`; when it has problems, reads every sample that can be read (a chunk that
// fails its checksum becomes a gap and is named), cuts the end that no flush completed (rows
// that hold nothing but gaps), writes a new recording of it in the current format, verifies
// that, renames the original to PATH.damaged (or .damaged-2, ...) and the new file to PATH.
// Throws tactile::Error naming the file when the file cannot be opened at all or the repaired
// copy cannot be written (no room): the original then stays as it was.
RepairReport repair_recording(const std::string& path);

// The lines `tactile repair` prints for one file: "PATH: whole, nothing to repair", or
// "PATH: repaired; the damaged original is kept as PATH.damaged" then "  rebuilt: ..." and
// "  lost: ..." lines.
std::vector<std::string> repair_lines(const std::string& path, const RepairReport& report);

}  // namespace tactile
