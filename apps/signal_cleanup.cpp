#include "signal_cleanup.hpp"

#include <limits.h>
#include <pthread.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <stdexcept>

namespace gyro::sil::signal_cleanup {

namespace {

enum State : int { kFree = 0, kFile = 1, kDirectory = 2 };

struct Slot {
  std::array<char, PATH_MAX> path{};
  volatile std::sig_atomic_t state{kFree};
};

constexpr std::size_t kSlots = 64;
constexpr std::array<int, 4> kSignals = {SIGINT, SIGTERM, SIGHUP, SIGPIPE};

// Append-only, so slot order is registration order (directories are removed newest first).
std::array<Slot, kSlots> g_slots;
std::size_t g_used = 0;
volatile std::sig_atomic_t g_child = 0;

extern "C" void on_signal(int sig) {
  const int saved_errno = errno;
  const pid_t child = static_cast<pid_t>(g_child);
  if (child > 0) ::kill(-child, SIGKILL);
  for (std::size_t i = 0; i < kSlots; ++i) {
    if (g_slots[i].state == kFile) ::unlink(g_slots[i].path.data());
  }
  for (std::size_t i = kSlots; i-- > 0;) {
    if (g_slots[i].state == kDirectory) ::rmdir(g_slots[i].path.data());
  }
  errno = saved_errno;
  // Blocked while this handler runs: delivered, with the default action, once it returns.
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

int add(const std::string& path, State state) {
  if (path.size() >= PATH_MAX) throw std::runtime_error("path too long to register for removal: " + path);
  if (g_used == kSlots) throw std::runtime_error("too many temporary paths to register for removal");
  Slot& s = g_slots[g_used];
  std::memcpy(s.path.data(), path.c_str(), path.size() + 1);
  std::atomic_signal_fence(std::memory_order_seq_cst);  // the path is complete before it is armed
  s.state = state;
  return static_cast<int>(g_used++);
}

}  // namespace

void install() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  for (int sig : kSignals) sigaddset(&sa.sa_mask, sig);  // one cleanup at a time
  for (int sig : kSignals) {
    struct sigaction old {};
    if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;  // keep what the caller ignores
    ::sigaction(sig, &sa, nullptr);
  }
}

int add_file(const std::string& path) { return add(path, kFile); }
int add_directory(const std::string& path) { return add(path, kDirectory); }

void forget(int slot) noexcept {
  if (slot >= 0 && static_cast<std::size_t>(slot) < kSlots) g_slots[static_cast<std::size_t>(slot)].state = kFree;
}

void set_child(pid_t process_group) noexcept { g_child = static_cast<std::sig_atomic_t>(process_group); }

Deferred::Deferred() noexcept {
  sigset_t block;
  sigemptyset(&block);
  for (int sig : kSignals) sigaddset(&block, sig);
  ::pthread_sigmask(SIG_BLOCK, &block, &old_);
}

Deferred::~Deferred() { ::pthread_sigmask(SIG_SETMASK, &old_, nullptr); }

}  // namespace gyro::sil::signal_cleanup
