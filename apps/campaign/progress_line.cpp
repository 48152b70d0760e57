#include "progress_line.hpp"

#include <unistd.h>

#include <cstdio>

namespace gyro::campaign {

ProgressLine::ProgressLine(std::uint64_t total, bool enabled)
    : total_(total),
      enabled_(enabled),
      tty_(::isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

void ProgressLine::advance(std::uint64_t runs) {
  done_ += runs;
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_ < (tty_ ? std::chrono::milliseconds(500) : std::chrono::milliseconds(10'000))) return;
  last_ = now;
  print(false);
}

void ProgressLine::finish() {
  if (enabled_) print(true);
}

void ProgressLine::print(bool final_line) {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double rate = elapsed > 0 ? static_cast<double>(done_) / elapsed : 0.0;
  const double left = rate > 0 ? static_cast<double>(total_ - done_) / rate : 0.0;
  const double share = total_ == 0 ? 1.0 : static_cast<double>(done_) / static_cast<double>(total_);
  char line[160];
  if (final_line) {
    std::snprintf(line, sizeof line, "gyro_campaign: %llu runs in %.1f s (%.1f runs/s)",
                  static_cast<unsigned long long>(done_), elapsed, rate);
  } else {
    std::snprintf(line, sizeof line, "gyro_campaign: %llu of %llu runs (%.1f %%), %.1f runs/s, %.0f s left",
                  static_cast<unsigned long long>(done_), static_cast<unsigned long long>(total_), 100.0 * share,
                  rate, left);
  }
  std::fprintf(stderr, tty_ ? "\r%-78s%s" : "%s%s\n", line, tty_ && final_line ? "\n" : "");
  std::fflush(stderr);
}

}  // namespace gyro::campaign
