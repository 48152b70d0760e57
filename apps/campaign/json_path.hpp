// JSON paths as scenarios name their fields: members by name, array elements by index,
// "gyro.rotor.pitch_inertia", "guidance.schedule[2].slew_rate_rad_s[0]". A campaign's
// dispersions and settings name scenario fields this way; a path that does not exist in the
// document is an error that says what does exist, never a field created on the fly.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace gyro::campaign {

struct PathStep {
  std::string key;         // a member name, or empty for an element
  std::size_t index{0};    // the element's index
  bool is_element{false};

  [[nodiscard]] static PathStep member(std::string name) { return PathStep{std::move(name), 0, false}; }
  [[nodiscard]] static PathStep element(std::size_t i) { return PathStep{{}, i, true}; }
};

// "a.b[2].c" -> steps; nullopt with `why` set when the text is not a path (empty, a name
// with characters other than letters, digits and '_', an index that is not a number).
[[nodiscard]] std::optional<std::vector<PathStep>> parse_path(std::string_view text, std::string& why);

// steps -> "a.b[2].c".
[[nodiscard]] std::string format_path(const std::vector<PathStep>& steps);

// The node at `steps` in `doc`; nullptr with `why` set (what is missing, what exists there,
// the nearest name) when there is none.
[[nodiscard]] nlohmann::json* find_path(nlohmann::json& doc, const std::vector<PathStep>& steps, std::string& why);
[[nodiscard]] const nlohmann::json* find_path(const nlohmann::json& doc, const std::vector<PathStep>& steps,
                                              std::string& why);

// The allowed name nearest to `key` by edit distance, if it is near enough to be a typo.
[[nodiscard]] std::optional<std::string> nearest_name(std::string_view key, const std::vector<std::string>& names);

}  // namespace gyro::campaign
