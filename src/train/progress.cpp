#include "train/progress.h"

#include <unistd.h>

#include <cstdio>

#include <fmt/format.h>

namespace glossa::train {

std::string format_duration(double s) {
  if (s < 0 || s > 1e7) return "?";
  const long t = static_cast<long>(s + 0.5);
  if (t >= 3600) return fmt::format("{}h{:02}m", t / 3600, (t / 60) % 60);
  if (t >= 60) return fmt::format("{}m{:02}s", t / 60, t % 60);
  return fmt::format("{}s", t);
}

ProgressBar::ProgressBar(std::string label, size_t total, bool enabled)
    : label_(std::move(label)),
      total_(total),
      enabled_(enabled),
      tty_(::isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

void ProgressBar::update(size_t done, const std::string& suffix) {
  if (!enabled_ || total_ == 0) return;
  const auto now = std::chrono::steady_clock::now();
  const double frac = std::min(1.0, double(done) / double(total_));
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double eta = frac > 0 ? elapsed * (1 - frac) / frac : -1;
  if (tty_) {
    if (done < total_ && now - last_draw_ < std::chrono::milliseconds(200)) return;
    last_draw_ = now;
    const int width = 24, fill = static_cast<int>(frac * width);
    std::fprintf(stderr, "\r%s [%s%s] %3d%% %s ETA %s   ", label_.c_str(),
                 std::string(fill, '=').c_str(), std::string(width - fill, ' ').c_str(),
                 static_cast<int>(frac * 100), suffix.c_str(), format_duration(eta).c_str());
    std::fflush(stderr);
  } else {
    if (now - last_draw_ < std::chrono::seconds(10)) return;
    last_draw_ = now;
    std::fprintf(stderr, "%s %3d%% %s ETA %s\n", label_.c_str(), static_cast<int>(frac * 100),
                 suffix.c_str(), format_duration(eta).c_str());
  }
}

void ProgressBar::finish(const std::string& suffix) {
  if (!enabled_) return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::fprintf(stderr, "%s%s done in %s %s\n", tty_ ? "\r" : "", label_.c_str(),
               format_duration(elapsed).c_str(), suffix.c_str());
}

}  // namespace glossa::train
