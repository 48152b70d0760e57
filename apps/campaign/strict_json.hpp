// JSON text -> document, refusing what nlohmann::json lets through silently: a key written
// twice in one object (the last one would win). Every refusal names the field's JSON path.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace gyro::campaign {

// Throws CampaignError(file, path, reason): "(document)" for text that is not JSON, the
// duplicated key's path ("gyro.rotor.friction") for a key written twice.
[[nodiscard]] nlohmann::json parse_strict_json(std::string_view text, const std::string& file);

}  // namespace gyro::campaign
