#pragma once
// Shared by the workbench benchmarks: percentiles of a run's times, and frames of the whole
// workbench drawn headless at 60 a second, as a window's swap would pace them.

#include <algorithm>
#include <chrono>
#include <thread>
#include <vector>

#include "osmesa_renderer.h"
#include "workbench.h"

namespace tactile::bench {

// The value at `fraction` (0 = least, 1 = most) of the sorted values; 0 for none.
inline double percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[static_cast<size_t>(fraction * static_cast<double>(values.size() - 1))];
}

// Draws one frame per call, then sleeps until the next sixtieth of a second; returns the
// frame's own time in ms (also kept in `ms`).
struct PacedFrames {
  using Clock = std::chrono::steady_clock;
  PacedFrames(int width, int height) : renderer(width, height) {}

  double draw(Workbench& workbench) {
    const auto begin = Clock::now();
    renderer.new_frame();
    workbench.frame(1.0 / 60.0);
    renderer.render();
    const double took = std::chrono::duration<double, std::milli>(Clock::now() - begin).count();
    ms.push_back(took);
    next += std::chrono::microseconds(16667);
    if (next > Clock::now())
      std::this_thread::sleep_until(next);
    else
      next = Clock::now();
    return took;
  }

  OffscreenRenderer renderer;
  Clock::time_point next = Clock::now();
  std::vector<double> ms;
};

}  // namespace tactile::bench
