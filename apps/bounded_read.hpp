// Reading a whole input file with a bound on its size, checked before reading: a regular file
// larger than the bound is refused from its size alone, and anything else (/dev/zero, a pipe,
// a file that grows) is refused after reading at most one buffer past the bound. The host
// tools read every input through it (docs/coding-rules.md, "every host input bounded").
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace gyro::sil {

// The file's bytes, or nullopt with `why` set: it cannot be opened or read, it is a directory,
// or it holds more than `max_bytes` ("the file has N bytes, more than the limit of M bytes for
// <what>"). `what` names the kind of input in that message ("a scenario", "a campaign file").
[[nodiscard]] std::optional<std::string> read_bounded(const std::string& name, std::uint64_t max_bytes,
                                                      const std::string& what, std::string& why);

}  // namespace gyro::sil
