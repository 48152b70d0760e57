#include "run_pool.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <system_error>

#include "campaign_run.hpp"
#include "run_table.hpp"

namespace gyro::campaign {

RunPool::RunPool(const Campaign& c, std::uint64_t first, std::uint64_t end, unsigned threads)
    : campaign_(c), end_(end), next_(first), remaining_(end > first ? end - first : 0) {
  if (threads > kMaxThreads) {
    throw std::invalid_argument("threads " + std::to_string(threads) + ": at most " + std::to_string(kMaxThreads));
  }
  const std::uint64_t n = std::max<std::uint64_t>(1, std::min<std::uint64_t>(threads, remaining_));
  try {
    for (std::uint64_t i = 0; i < n; ++i) workers_.emplace_back([this] { work(); });
  } catch (const std::system_error& e) {
    next_.store(end_);
    for (std::thread& t : workers_) t.join();
    throw std::runtime_error("cannot start worker thread " + std::to_string(workers_.size() + 1) + " of " +
                             std::to_string(n) + ": " + e.what());
  }
}

RunPool::~RunPool() {
  next_.store(end_);  // no new runs once the owner gives up (e.g. after a failure)
  for (std::thread& t : workers_) t.join();
}

void RunPool::work() {
  try {
    for (std::uint64_t k = next_.fetch_add(1); k < end_; k = next_.fetch_add(1)) {
      std::string row = format_row(campaign_, execute_run(campaign_, k));
      const std::lock_guard<std::mutex> lock(mutex_);
      finished_.push_back(std::move(row));
      if (finished_.size() == remaining_) ready_.notify_one();  // the last: no need to wait longer
    }
  } catch (...) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!failure_) failure_ = std::current_exception();
    next_.store(end_);
    ready_.notify_one();
  }
}

std::vector<std::string> RunPool::take(std::chrono::milliseconds wait) {
  std::unique_lock<std::mutex> lock(mutex_);
  // Woken by the last run or a failure only: the owner collects in batches, not per run.
  ready_.wait_for(lock, wait, [this] { return failure_ || finished_.size() == remaining_; });
  if (failure_) std::rethrow_exception(failure_);
  std::vector<std::string> out;
  out.swap(finished_);
  remaining_ -= out.size();
  return out;
}

bool RunPool::done() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return remaining_ == 0;
}

}  // namespace gyro::campaign
