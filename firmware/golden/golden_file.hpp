// What the golden-value generators share: C++ literals for the values, and writing the
// header or checking that the committed one is current.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
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

// glibc picks its exp/sin/cos by CPU (FMA or not), so two x86-64 hosts can print values a few
// ulp apart, and the float closed loop carries such differences on. A value is stale when it
// moved by more than 1e-5 of itself + 1e-6 (float) or 1e-13 of itself + 1e-15 (double): far
// below what the targets may deviate (firmware/tests: float 5e-5 of scale or 2e-4 rad, double
// 1e-12 of scale or 1e-9 rad), and above what newlib on the M4F does (6e-8 rad, 2.7e-7 rad/s).
inline bool same_literal(const std::string& a, const std::string& b) {
  if (a == b) return true;
  const bool is_real = a.find_first_of(".e") != std::string::npos;
  if (!is_real || b.find_first_of(".e") == std::string::npos) return false;
  const bool is_float = a.back() == 'f';
  if (is_float != (b.back() == 'f')) return false;
  char* end_a = nullptr;
  char* end_b = nullptr;
  const double x = std::strtod(a.c_str(), &end_a);
  const double y = std::strtod(b.c_str(), &end_b);
  if (end_a != a.c_str() + a.size() - (is_float ? 1 : 0)) return false;
  if (end_b != b.c_str() + b.size() - (is_float ? 1 : 0)) return false;
  const double rel = is_float ? 1e-5 : 1e-13;
  const double abs = is_float ? 1e-6 : 1e-15;
  return std::fabs(x - y) <= rel * std::fmax(std::fabs(x), std::fabs(y)) + abs;
}

// Token by token (blanks separate; a comma or brace is a token of its own): text identical,
// reals within same_literal. Returns the line of the first disagreement in `want`, or 0, and
// the two tokens in `what`.
inline std::size_t first_stale_line(const std::string& have, const std::string& want, std::string& what) {
  const auto is_blank = [](char c) { return c == ' ' || c == '\n'; };
  const auto is_punct = [](char c) { return c == ',' || c == '{' || c == '}'; };
  const auto token_end = [&](const std::string& s, std::size_t k) {
    if (is_punct(s[k])) return k + 1;
    while (k < s.size() && !is_blank(s[k]) && !is_punct(s[k])) ++k;
    return k;
  };
  std::size_t i = 0, j = 0, line = 1;
  for (;;) {
    while (i < have.size() && is_blank(have[i])) ++i;
    while (j < want.size() && is_blank(want[j])) line += want[j++] == '\n' ? 1U : 0U;
    if (i == have.size() || j == want.size()) {
      what = "one ends before the other";
      return i == have.size() && j == want.size() ? 0 : line;
    }
    const std::size_t ie = token_end(have, i), je = token_end(want, j);
    if (!same_literal(have.substr(i, ie - i), want.substr(j, je - j))) {
      what = "file has " + have.substr(i, ie - i) + ", this host computes " + want.substr(j, je - j);
      return line;
    }
    i = ie;
    j = je;
  }
}

// argv: <file> writes `text` to it; --check <file> returns 1 unless the file holds `text`
// (up to first_stale_line).
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
    std::string what;
    const std::size_t line = first_stale_line(have, text, what);
    if (line != 0) {
      std::fprintf(stderr,
                   "%s is stale (first difference at line %zu: %s): regenerate with\n"
                   "  cmake --build --preset host --target %s\n",
                   path, line, what.c_str(), update_target);
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
