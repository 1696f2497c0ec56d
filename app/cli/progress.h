#pragma once
// A one-line progress bar on stderr, redrawn in place; silent when stderr is not a terminal
// except for the final line, so logs stay readable.

#include <chrono>
#include <string>

namespace tactile::cli {

class ProgressBar {
 public:
  explicit ProgressBar(std::string task);
  void update(int64_t done, int64_t total);
  void finish();

 private:
  std::string task_;
  bool terminal_;
  int64_t done_ = 0;
  int64_t total_ = 0;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace tactile::cli
