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

// Most worker threads a process starts (gyro_campaign -j): a run keeps one core busy, so more
// threads than cores only share them; the bound keeps a mistyped count from asking the system
// for more threads than it gives (a request it refuses would end the process).
inline constexpr unsigned kMaxThreads = 1024;

class RunPool {
 public:
  // Starts min(threads, end - first) workers (at least one). Throws std::invalid_argument for
  // more than kMaxThreads, std::runtime_error when the system refuses a thread (the workers
  // started are stopped and joined first).
  RunPool(const Campaign& c, std::uint64_t first, std::uint64_t end, unsigned threads);
  ~RunPool();
  RunPool(const RunPool&) = delete;
  RunPool& operator=(const RunPool&) = delete;

  // The rows finished since the last call (each a run's table row, '\n'-terminated), after
  // `wait` or as soon as every run has finished. Rethrows what a worker threw.
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

}  // namespace gyro::campaign
