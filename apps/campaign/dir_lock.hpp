// The lock of an output directory: one gyro_campaign at a time writes into a directory. The
// lock is an advisory lock (flock) on the file .gyro_campaign.lock in it, held while the
// process lives: the kernel releases it however the process ends, and the file itself is
// removed on exit and by the signal handler of signal_cleanup.hpp (SIGINT, SIGTERM, SIGHUP,
// SIGPIPE). A second run into a locked directory is refused at once, naming the process that
// holds it.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace gyro::campaign {

inline constexpr const char* kLockFile = ".gyro_campaign.lock";

class DirectoryLock {
 public:
  // Locks `dir` (an existing directory), or nullopt with `why` set: another process holds it,
  // or the lock file cannot be made (a symbolic link in its place is refused, not followed).
  [[nodiscard]] static std::optional<DirectoryLock> take(const std::filesystem::path& dir, std::string& why);

  DirectoryLock(DirectoryLock&& other) noexcept;
  DirectoryLock& operator=(DirectoryLock&& other) noexcept;
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;
  ~DirectoryLock();

 private:
  DirectoryLock() = default;
  void release() noexcept;
  std::filesystem::path path_;
  int fd_{-1};
  int slot_{-1};  // in signal_cleanup's registry
};

}  // namespace gyro::campaign
