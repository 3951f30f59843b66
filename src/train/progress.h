#pragma once
// A one-line progress bar on stderr with a rate and an ETA. On a terminal it redraws in
// place; otherwise (CI logs, files) it prints at most one line every 10 s so logs stay short.
#include <chrono>
#include <string>

namespace glossa::train {

class ProgressBar {
 public:
  ProgressBar(std::string label, size_t total, bool enabled = true);
  void update(size_t done, const std::string& suffix = "");
  void finish(const std::string& suffix = "");

 private:
  std::string label_;
  size_t total_;
  bool enabled_, tty_;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

std::string format_duration(double seconds);

}  // namespace glossa::train
