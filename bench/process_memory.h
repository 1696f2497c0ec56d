#pragma once
// The benchmarks' memory figures: this process's peak resident memory (Linux's VmHWM), and a
// reset of that peak so that each measured step starts from what is resident now.

#include <unistd.h>

#include <fstream>
#include <string>

namespace tactile::bench {

// Peak resident memory in MB since the start or the last reset_peak_memory(); 0 off Linux.
inline double peak_memory_mb() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return 0.0;
}

// Starts the peak again from the memory resident now (writing 5 to clear_refs).
// Resident memory now (MB): /proc/self/statm's second field, in pages.
inline double resident_memory_mb() {
  std::ifstream statm("/proc/self/statm");
  long size = 0, resident = 0;
  statm >> size >> resident;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / 1e6;
}

inline void reset_peak_memory() { std::ofstream("/proc/self/clear_refs") << "5"; }

}  // namespace tactile::bench
