#include "option_values.hpp"

#include <charconv>

#include "printable.hpp"

namespace gyro::campaign {

std::optional<std::uint64_t> parse_count(const std::string& option, const std::string& text, std::uint64_t max,
                                         std::string& why) {
  const std::string expected = "expected a whole number from 0 to " + std::to_string(max);
  if (text.empty()) {
    why = option + " is empty: " + expected;
    return std::nullopt;
  }
  std::uint64_t v = 0;
  const char* end = text.data() + text.size();
  const std::from_chars_result r = std::from_chars(text.data(), end, v);
  const bool digits_only = text.find_first_not_of("0123456789") == std::string::npos;
  if (!digits_only || r.ec == std::errc::invalid_argument || r.ptr != end) {
    why = option + " " + sil::printable(text) + ": " + expected;
    return std::nullopt;
  }
  if (r.ec == std::errc::result_out_of_range || v > max) {
    why = option + " " + sil::printable(text) + ": more than the limit of " + std::to_string(max);
    return std::nullopt;
  }
  return v;
}

}  // namespace gyro::campaign
