#include "dir_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <utility>

#include "printable.hpp"
#include "signal_cleanup.hpp"

namespace gyro::campaign {

namespace {

// The process id the holder wrote into the lock file ("" if none could be read).
std::string holder_of(int fd) {
  std::array<char, 32> buf{};
  const ::ssize_t n = ::pread(fd, buf.data(), buf.size() - 1, 0);
  if (n <= 0) return "";
  std::string s(buf.data(), static_cast<std::size_t>(n));
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s.find_first_not_of("0123456789") == std::string::npos ? s : "";
}

}  // namespace

std::optional<DirectoryLock> DirectoryLock::take(const std::filesystem::path& dir, std::string& why) {
  const std::filesystem::path path = dir / kLockFile;
  const std::string name = "\"" + sil::printable(path.string()) + "\"";
  // A holder that ends between our open and our flock removes the file it held: the file we
  // locked is then no longer the one at the path, and we try again with a fresh one.
  for (int attempt = 0; attempt < 8; ++attempt) {
    DirectoryLock lock;
    {
      const sil::signal_cleanup::Deferred opened_then_registered;
      lock.fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC | O_NOCTTY, 0644);
      if (lock.fd_ < 0) {
        why = errno == ELOOP ? "the lock file " + name + " is a symbolic link: refused, not followed"
                             : "cannot create the lock file " + name + ": " + std::strerror(errno);
        return std::nullopt;
      }
      if (::flock(lock.fd_, LOCK_EX | LOCK_NB) != 0) {
        const int e = errno;
        if (e != EWOULDBLOCK) {
          why = "cannot lock " + name + ": " + std::strerror(e);
          return std::nullopt;
        }
        const std::string pid = holder_of(lock.fd_);
        why = "the output directory \"" + sil::printable(dir.string()) + "\" is in use by another gyro_campaign" +
              (pid.empty() ? std::string() : " (process " + pid + ")") + ": wait for it to end, or choose another directory";
        return std::nullopt;
      }
      struct stat held {}, named {};
      if (::fstat(lock.fd_, &held) != 0 || ::lstat(path.c_str(), &named) != 0 || held.st_dev != named.st_dev ||
          held.st_ino != named.st_ino) {
        continue;  // `lock` closes the stale descriptor; its path is not set, so nothing is removed
      }
      lock.path_ = path;
      lock.slot_ = sil::signal_cleanup::add_file(path.string());
    }
    // The process id, for the message of a refused run; the lock holds without it.
    const std::string pid = std::to_string(::getpid()) + "\n";
    const bool noted = ::ftruncate(lock.fd_, 0) == 0 && ::pwrite(lock.fd_, pid.data(), pid.size(), 0) >= 0;
    (void)noted;
    return lock;
  }
  why = "cannot lock " + name + ": it keeps being replaced";
  return std::nullopt;
}

DirectoryLock::DirectoryLock(DirectoryLock&& o) noexcept
    : path_(std::move(o.path_)), fd_(std::exchange(o.fd_, -1)), slot_(std::exchange(o.slot_, -1)) {
  o.path_.clear();
}

DirectoryLock& DirectoryLock::operator=(DirectoryLock&& o) noexcept {
  if (this != &o) {
    release();
    path_ = std::move(o.path_);
    o.path_.clear();
    fd_ = std::exchange(o.fd_, -1);
    slot_ = std::exchange(o.slot_, -1);
  }
  return *this;
}

DirectoryLock::~DirectoryLock() { release(); }

void DirectoryLock::release() noexcept {
  // Removed while still locked, so that no other process can lock this file in between.
  if (!path_.empty()) ::unlink(path_.c_str());
  path_.clear();
  sil::signal_cleanup::forget(slot_);
  slot_ = -1;
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

}  // namespace gyro::campaign
