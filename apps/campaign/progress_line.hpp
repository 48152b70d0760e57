// gyro_campaign's progress on standard error.
#pragma once

#include <chrono>
#include <cstdint>

namespace gyro::campaign {

// The progress line on standard error: runs done, the run rate and the time left. On a
// terminal it is redrawn in place twice a second; otherwise a line every 10 s.
class ProgressLine {
 public:
  ProgressLine(std::uint64_t total, bool enabled);
  void advance(std::uint64_t runs);
  void finish();

 private:
  void print(bool final_line);

  std::uint64_t total_, done_{0};
  bool enabled_, tty_;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace gyro::campaign
