// JSON text -> document, refusing what nlohmann::json lets through silently: a key written
// twice in one object (the last one would win). Every refusal names the field's JSON path.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace gyro::campaign {

// Deepest nesting of arrays and objects accepted: a base scenario inline (the scenario's own
// bound is 16 levels) inside the campaign, with room to spare. Deeper text is refused while
// it is parsed, before any copy or dump (which recurse: 10^6 levels overflowed the stack).
inline constexpr std::size_t kMaxCampaignDepth = 32;

// Throws CampaignError(file, path, reason): "(document)" for text that is not JSON, the
// duplicated key's path ("gyro.rotor.friction") for a key written twice, the path of the
// container that opens level kMaxCampaignDepth + 1.
[[nodiscard]] nlohmann::json parse_strict_json(std::string_view text, const std::string& file);

}  // namespace gyro::campaign
