#include "progress.h"

#include <unistd.h>

#include <cstdio>

namespace tactile::cli {

ProgressBar::ProgressBar(std::string task)
    : task_(std::move(task)),
      terminal_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()) {}

void ProgressBar::update(int64_t done, int64_t total) {
  done_ = done;
  total_ = total;
  if (!terminal_) return;
  const auto now = std::chrono::steady_clock::now();
  if (done < total && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  const int width = 30;
  const int filled = total > 0 ? static_cast<int>(width * done / total) : 0;
  std::fprintf(stderr, "\r%s [%.*s%*s] %lld/%lld", task_.c_str(), filled,
               "##############################", width - filled, "", static_cast<long long>(done),
               static_cast<long long>(total));
  std::fflush(stderr);
}

void ProgressBar::finish() {
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (terminal_) std::fprintf(stderr, "\r\033[K");
  std::fprintf(stderr, "%s: %lld/%lld done in %.1f s\n", task_.c_str(),
               static_cast<long long>(done_), static_cast<long long>(total_), seconds);
}

}  // namespace tactile::cli
