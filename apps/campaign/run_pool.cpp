#include "run_pool.hpp"

#include <unistd.h>

#include <cstdio>

#include "campaign_run.hpp"
#include "run_table.hpp"

namespace gyro::campaign {

RunPool::RunPool(const Campaign& c, std::uint64_t first, std::uint64_t end, unsigned threads)
    : campaign_(c), end_(end), next_(first), remaining_(end > first ? end - first : 0) {
  const unsigned n = threads == 0 ? 1u : threads;
  for (unsigned i = 0; i < n; ++i) workers_.emplace_back([this] { work(); });
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
      ready_.notify_one();
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
  ready_.wait_for(lock, wait, [this] { return !finished_.empty() || failure_ || remaining_ == 0; });
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
