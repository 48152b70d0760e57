// What a scenario builds on: one of the example gyros (`"example": "seeker"`) or another
// scenario file (`"base": "seeker_slew.json"`), its own sections merged over it as a JSON
// merge patch (RFC 7386: objects merged key by key, arrays and values replaced, null removes
// a key, so that its default applies). docs/scenarios.md, "Examples and bases".
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace gyro::sil {

// A chain of bases (a base's base ...) longer than this is refused: it bounds the files read
// and ends a cycle.
inline constexpr std::size_t kMaxScenarioBases = 4;

// The example gyros a scenario may name, as their "gyro" and (where the example defines the
// flight side) "component" sections: the C++ headers of examples/include/gyro/ written in
// their shortest scenario form (a field whose scenario default is the example's value, such as
// the bearings' friction taken from the rotor's, is left out, so that it follows the field it
// derives from under a campaign's dispersions). Throws ScenarioError naming `file`'s
// "example" for an unknown name.
[[nodiscard]] nlohmann::json example_sections(std::string_view name, const std::string& file);

// The names example_sections() knows, ", "-separated.
[[nodiscard]] std::string example_names();

// `doc` with its "example" or "base" expanded (recursively, at most kMaxScenarioBases deep),
// the key removed; a document with neither is returned as it is. A base's path is relative
// to `dir`, read bounded like any scenario. Throws ScenarioError naming `file` and the key.
[[nodiscard]] nlohmann::json resolve_scenario_base(const nlohmann::json& doc, const std::filesystem::path& dir,
                                                   const std::string& file);

}  // namespace gyro::sil
