// gyro_campaign's option values, read strictly: a count is decimal digits only, within its
// bound. An empty value, a sign, a fraction, an exponent, "nan" or "inf", or a number past
// the bound is refused with a message naming the option, the value and the bound; nothing is
// read as "no limit" or as the default. (CLI11 would wrap "-1" to the largest unsigned value
// and take "" as unset.)
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace gyro::campaign {

// `text` as an integer in [0, max], or nullopt with `why` set ("-j 5000: more than the
// limit of 1024", "-j -1: expected a whole number from 0 to 1024").
[[nodiscard]] std::optional<std::uint64_t> parse_count(const std::string& option, const std::string& text,
                                                       std::uint64_t max, std::string& why);

}  // namespace gyro::campaign
