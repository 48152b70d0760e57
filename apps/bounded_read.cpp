#include "bounded_read.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>

namespace gyro::sil {

namespace {

struct Descriptor {
  int fd;
  ~Descriptor() { ::close(fd); }
};

}  // namespace

std::optional<std::string> read_bounded(const std::string& name, std::uint64_t max_bytes, const std::string& what,
                                        std::string& why) {
  const int fd = ::open(name.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) {
    why = std::string("cannot open the file for reading: ") + std::strerror(errno);
    return std::nullopt;
  }
  const Descriptor closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    why = std::string("cannot stat the file: ") + std::strerror(errno);
    return std::nullopt;
  }
  if (S_ISDIR(st.st_mode)) {
    why = "is a directory, not " + what + " file";
    return std::nullopt;
  }
  const std::string limit = "the limit of " + std::to_string(max_bytes) + " bytes for " + what;
  if (S_ISREG(st.st_mode) && static_cast<std::uint64_t>(st.st_size) > max_bytes) {
    why = "the file has " + std::to_string(st.st_size) + " bytes, more than " + limit;
    return std::nullopt;
  }
  std::string text;
  std::array<char, 65536> buf{};
  while (true) {
    const ::ssize_t n = ::read(fd, buf.data(), buf.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      why = std::string("read error: ") + std::strerror(errno);
      return std::nullopt;
    }
    if (n == 0) break;
    text.append(buf.data(), static_cast<std::size_t>(n));
    if (text.size() > max_bytes) {
      why = "gave more than " + limit + " (stopped reading)";
      return std::nullopt;
    }
  }
  return text;
}

}  // namespace gyro::sil
