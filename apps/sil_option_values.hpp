// gyro_sil's option values that CLI11 would convert silently: byte sizes (a negative number
// wraps to a huge unsigned one), time limits (NaN and infinity pass a "> 0" test or fail it
// without a word) and strings (an empty one reads as "not given"). Each is parsed here whole,
// checked against its bound, and refused with a message that names the option, its value (as
// printable(): control characters escaped) and the bound:
//
//   --max-output-bytes "-1": not a byte count: digits, optionally a unit (...)
//   --pil-timeout "nan": not a finite number of seconds; give a value > 0 and <= 3600
//   --plot "": empty; give a file name
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace gyro::sil {

// The longest a time limit may be: gnuplot may run a day (--plot-timeout), the target may stay
// silent an hour (--pil-timeout). Both bounds keep the limit's milliseconds within an int
// (poll()'s argument: 2^31 ms is 24.8 days).
inline constexpr double kMaxPlotTimeoutS = 86400.0;
inline constexpr double kMaxPilTimeoutS = 3600.0;

// `"text"` with control characters escaped: how an option's value is shown in messages.
[[nodiscard]] std::string quoted_value(std::string_view text);

// A size in bytes: digits, then optionally (spaces and) a unit, case-insensitive: B, kB or K
// (1000), KiB or Ki (1024), MB, MiB, GB, GiB, TB, TiB, PB, PiB, EB, EiB. At least 1 and at most
// 2^64 - 1 bytes; nothing turns the bound off. nullopt, with `error` set, when refused.
[[nodiscard]] std::optional<std::uint64_t> parse_byte_size(std::string_view option, std::string_view text,
                                                           std::string& error);

// Seconds: a decimal number, the whole text (no spaces, no "+"), finite, > 0 and <= max_s.
[[nodiscard]] std::optional<double> parse_seconds(std::string_view option, std::string_view text, double max_s,
                                                  std::string& error);

// A string option's value: refused when empty (`what` says what to give instead: "a file
// name"). True when accepted.
[[nodiscard]] bool check_not_empty(std::string_view option, std::string_view text, std::string_view what,
                                   std::string& error);

}  // namespace gyro::sil
