#include "pil_connection.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

#include "sil_runner.hpp"

extern char** environ;

namespace gyro::sil {

namespace {

using Clock = std::chrono::steady_clock;

std::string errno_text() { return std::strerror(errno); }

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace

SerialSocket::SerialSocket(const std::string& path, double wait_s, const std::function<bool()>& still_starting) {
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  if (path.empty() || path.size() >= sizeof(addr.sun_path)) {
    throw RunError("PIL socket path '" + path + "' is empty or longer than " +
                   std::to_string(sizeof(addr.sun_path) - 1) + " bytes");
  }
  std::memcpy(addr.sun_path, path.c_str(), path.size() + 1);
  const Clock::time_point t0 = Clock::now();
  for (;;) {
    fd_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd_ < 0) throw RunError("socket(): " + errno_text());
    if (::connect(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0) return;
    const int err = errno;
    ::close(fd_);
    fd_ = -1;
    const bool may_appear = err == ENOENT || err == ECONNREFUSED;
    if (!may_appear || seconds_since(t0) > wait_s || !still_starting()) {
      throw RunError("cannot connect to the PIL socket " + path + ": " + std::strerror(err));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

SerialSocket::~SerialSocket() {
  if (fd_ >= 0) ::close(fd_);
}

void SerialSocket::write(std::span<const std::uint8_t> bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::send(fd_, bytes.data() + done, bytes.size() - done, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw RunError("PIL link: sending to the target failed: " + errno_text());
    done += static_cast<std::size_t>(n);
  }
}

std::uint8_t SerialSocket::read_byte(double timeout_s) {
  if (begin_ == end_) {
    const Clock::time_point t0 = Clock::now();
    for (;;) {
      const double left = timeout_s - seconds_since(t0);
      if (left <= 0) throw RunError("PIL link: no answer from the target for " + std::to_string(timeout_s) + " s");
      pollfd p{fd_, POLLIN, 0};
      const int r = ::poll(&p, 1, static_cast<int>(left * 1000.0) + 1);
      if (r < 0 && errno == EINTR) continue;
      if (r < 0) throw RunError("PIL link: poll(): " + errno_text());
      if (r == 0) continue;
      const ssize_t n = ::recv(fd_, buf_.data(), buf_.size(), 0);
      if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
      if (n < 0) throw RunError("PIL link: receiving failed: " + errno_text());
      if (n == 0) throw RunError("PIL link: the target closed the line (did it stop or crash?)");
      begin_ = 0;
      end_ = static_cast<std::size_t>(n);
      break;
    }
  }
  return buf_[begin_++];
}

bool SerialSocket::wait_closed(double timeout_s) {
  begin_ = end_ = 0;
  const Clock::time_point t0 = Clock::now();
  for (;;) {
    const double left = timeout_s - seconds_since(t0);
    if (left <= 0) return false;
    pollfd p{fd_, POLLIN, 0};
    const int r = ::poll(&p, 1, static_cast<int>(left * 1000.0) + 1);
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) return false;
    if (r == 0) continue;
    const ssize_t n = ::recv(fd_, buf_.data(), buf_.size(), 0);
    if (n == 0 || (n < 0 && errno != EINTR && errno != EAGAIN)) return true;
  }
}

QemuProcess::QemuProcess(const std::vector<std::string>& argv, bool console) {
  std::vector<char*> args;
  args.reserve(argv.size() + 1);
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  // The target's console (semihosting, on QEMU's stderr with -display none) and QEMU's own
  // messages: to our stderr, never to our stdout (which may carry the CSV).
  if (console) {
    posix_spawn_file_actions_adddup2(&actions, STDERR_FILENO, STDOUT_FILENO);
  } else {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  }
  const int rc = ::posix_spawnp(&pid_, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw RunError("cannot start " + argv[0] + ": " + std::strerror(rc));
}

QemuProcess::~QemuProcess() { terminate(); }

bool QemuProcess::running() {
  if (pid_ < 0) return false;
  int st = 0;
  const pid_t r = ::waitpid(pid_, &st, WNOHANG);
  if (r == 0) return true;
  if (r == pid_) status_ = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
  pid_ = -1;
  return false;
}

int QemuProcess::wait(double timeout_s) {
  const Clock::time_point t0 = Clock::now();
  while (running()) {
    if (seconds_since(t0) > timeout_s) {
      terminate();
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return status_;
}

void QemuProcess::terminate() {
  if (pid_ < 0) return;
  ::kill(pid_, SIGTERM);
  for (int i = 0; i < 200 && running(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  if (pid_ >= 0) {
    ::kill(pid_, SIGKILL);
    int st = 0;
    ::waitpid(pid_, &st, 0);
    pid_ = -1;
  }
}

std::vector<std::string> qemu_command(const std::string& qemu, const std::string& machine, const std::string& firmware,
                                      const std::string& socket) {
  // -icount shift=0,sleep=off: one instruction per nanosecond of virtual time, and idle time
  // (waiting for the next tick) skipped at once: timing is a function of the instructions.
  return {qemu,
          "-M",
          machine,
          "-display",
          "none",
          "-monitor",
          "none",
          "-icount",
          "shift=0,sleep=off",
          "-chardev",
          "socket,id=pil,path=" + socket + ",server=on,wait=on",
          "-serial",
          "chardev:pil",
          "-semihosting-config",
          "enable=on,target=native",
          "-kernel",
          firmware};
}

}  // namespace gyro::sil
