#include "sil_option_values.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <locale>
#include <sstream>
#include <system_error>

#include "printable.hpp"

namespace gyro::sil {

namespace {

std::string number_text(double v) {
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s << v;
  return s.str();
}

char lower(char c) noexcept { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

// The unit's factor (as CLI's AsSizeValue(true) had them: k = kB = 1000, Ki = KiB = 1024, ...);
// nullopt for an unknown unit or one past 2^64.
std::optional<std::uint64_t> unit_factor(std::string_view unit) {
  std::string u;
  for (char c : unit) u.push_back(lower(c));
  if (u.empty() || u == "b") return 1;
  constexpr std::array<char, 6> kPrefixes = {'k', 'm', 'g', 't', 'p', 'e'};
  std::uint64_t decimal = 1, binary = 1;
  for (char p : kPrefixes) {
    decimal *= 1000u;
    binary *= 1024u;
    const std::string s(1, p);
    if (u == s || u == s + "b") return decimal;
    if (u == s + "i" || u == s + "ib") return binary;
  }
  return std::nullopt;
}

}  // namespace

std::string quoted_value(std::string_view text) { return "\"" + printable(text) + "\""; }

std::optional<std::uint64_t> parse_byte_size(std::string_view option, std::string_view text, std::string& error) {
  const std::string head = std::string(option) + " " + quoted_value(text) + ": ";
  const std::string form = "digits, optionally with a unit (B, kB = 1000 B, KiB, MB, MiB, GB, GiB, ... EiB)";
  std::size_t digits = 0;
  while (digits < text.size() && text[digits] >= '0' && text[digits] <= '9') ++digits;
  if (digits == 0) {
    error = head + (text.empty() ? "empty; give a byte count: " : "not a byte count: ") + form;
    return std::nullopt;
  }
  std::uint64_t count = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + digits, count);
  if (digits < text.size() && text[digits] == '.') {
    error = head + "not a whole number of bytes: " + form;
    return std::nullopt;
  }
  std::size_t unit_at = digits;
  while (unit_at < text.size() && text[unit_at] == ' ') ++unit_at;
  const std::optional<std::uint64_t> factor = unit_factor(text.substr(unit_at));
  if (!factor) {
    error = head + "unknown unit " + quoted_value(text.substr(unit_at)) + ": " + form;
    return std::nullopt;
  }
  constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();
  if (ec == std::errc::result_out_of_range || end != text.data() + digits || (count != 0 && *factor > kMax / count)) {
    error = head + "more than the largest size, " + std::to_string(kMax) + " bytes";
    return std::nullopt;
  }
  if (count == 0) {
    error = head + "must be at least 1 byte";
    return std::nullopt;
  }
  return count * *factor;
}

std::optional<double> parse_seconds(std::string_view option, std::string_view text, double max_s,
                                    std::string& error) {
  const std::string head = std::string(option) + " " + quoted_value(text) + ": ";
  const std::string bound = "give seconds > 0 and <= " + number_text(max_s);
  double v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty()) {
    error = head + "empty; " + bound;
  } else if (ec == std::errc::result_out_of_range) {
    error = head + "out of range; " + bound;
  } else if (ec != std::errc() || end != text.data() + text.size()) {
    error = head + "not a number; " + bound;
  } else if (!std::isfinite(v)) {
    error = head + "not a finite number of seconds; " + bound;
  } else if (!(v > 0)) {
    error = head + "not > 0; " + bound;
  } else if (v > max_s) {
    error = head + "more than the limit of " + number_text(max_s) + " s; " + bound;
  } else {
    return v;
  }
  return std::nullopt;
}

bool check_not_empty(std::string_view option, std::string_view text, std::string_view what, std::string& error) {
  if (!text.empty()) return true;
  error = std::string(option) + " \"\": empty; give " + std::string(what);
  return false;
}

}  // namespace gyro::sil
