// Runs a range of a campaign's runs on worker threads. Workers take the next run index from
// a shared counter (so a slow run never holds up the others); each run's row depends only on
// (campaign, run index), so the order runs finish in does not matter. The thread that owns
// the pool collects the rows (and talks to MPI: workers never do).
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "campaign_file.hpp"

namespace gyro::campaign {

class RunPool {
 public:
  RunPool(const Campaign& c, std::uint64_t first, std::uint64_t end, unsigned threads);
  ~RunPool();
  RunPool(const RunPool&) = delete;
  RunPool& operator=(const RunPool&) = delete;

  // The rows finished since the last call (each a run's table row, '\n'-terminated), waiting
  // up to `wait` for one. Rethrows what a worker threw.
  [[nodiscard]] std::vector<std::string> take(std::chrono::milliseconds wait);
  // Every run finished and taken.
  [[nodiscard]] bool done() const;

 private:
  void work();

  const Campaign& campaign_;
  const std::uint64_t end_;
  std::atomic<std::uint64_t> next_;
  std::uint64_t remaining_;  // not yet taken
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::vector<std::string> finished_;
  std::exception_ptr failure_;
  std::vector<std::thread> workers_;
};

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
