// What the golden-value generators share: C++ literals for the values, and writing the
// header or checking that the committed one is current.
#pragma once

#include <cstdio>
#include <cstring>
#include <string>

namespace gyro_fw {

inline void append_real(std::string& out, double v, bool is_float) {
  char buf[64];
  std::snprintf(buf, sizeof buf, is_float ? "%.9g" : "%.17g", v);
  std::string s(buf);
  if (s.find_first_of(".en") == std::string::npos) s += ".0";
  if (is_float) s += "f";
  out += s;
}

// argv: <file> writes `text` to it; --check <file> returns 1 unless the file holds `text`.
inline int write_or_check(int argc, char** argv, const std::string& text, const char* update_target) {
  const bool check = argc == 3 && std::strcmp(argv[1], "--check") == 0;
  if (!(argc == 2 || check)) {
    std::fprintf(stderr, "usage: %s [--check] <header>\n", argv[0]);
    return 2;
  }
  const char* path = argv[argc - 1];
  if (check) {
    std::string have;
    if (std::FILE* f = std::fopen(path, "rb")) {
      char buf[4096];
      std::size_t n;
      while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) have.append(buf, n);
      std::fclose(f);
    }
    if (have != text) {
      std::size_t i = 0;
      while (i < have.size() && i < text.size() && have[i] == text[i]) ++i;
      std::size_t line = 1;
      for (std::size_t k = 0; k < i; ++k) line += text[k] == '\n' ? 1U : 0U;
      std::fprintf(stderr,
                   "%s is stale (first difference at line %zu): regenerate with\n"
                   "  cmake --build --preset host --target %s\n",
                   path, line, update_target);
      return 1;
    }
    std::printf("%s is up to date\n", path);
    return 0;
  }
  std::FILE* f = std::fopen(path, "wb");
  if (f == nullptr || std::fwrite(text.data(), 1, text.size(), f) != text.size()) {
    std::fprintf(stderr, "cannot write %s\n", path);
    return 1;
  }
  std::fclose(f);
  std::printf("wrote %s\n", path);
  return 0;
}

}  // namespace gyro_fw
