// The host tools' output files: opened for writing, or a line on stderr saying which could not be.
#pragma once

#include <cstdio>
#include <string>

namespace gyro::tools {

// `path` opened for writing; nullptr, said on stderr, when it cannot be.
[[nodiscard]] inline std::FILE* open_for_writing(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) std::fprintf(stderr, "cannot write %s\n", path.c_str());
  return f;
}

// `text` written to `path`; false when it could not be.
[[nodiscard]] inline bool write_text_file(const std::string& path, const std::string& text) {
  std::FILE* f = open_for_writing(path);
  if (f == nullptr) return false;
  const bool written = std::fputs(text.c_str(), f) >= 0;
  return std::fclose(f) == 0 && written;
}

}  // namespace gyro::tools
