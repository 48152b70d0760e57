// The strict JSON layer under every file format the tools read (scenarios, campaigns,
// manifests): text -> document refusing what nlohmann::json lets through silently (a key
// written twice, the last one winning), objects checked against their allowed keys, and the
// JSON paths that name a field in every refusal. Each format rethrows a JsonRefusal as its
// own error, with its file name.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

namespace gyro::sil {

// A refusal: the field as a JSON path ("gyro.rotor.friction", "(root)", "(document)") and why.
class JsonRefusal : public std::runtime_error {
 public:
  JsonRefusal(std::string field, std::string reason)
      : std::runtime_error(field + ": " + reason), field_(std::move(field)), reason_(std::move(reason)) {}
  [[nodiscard]] const std::string& field() const noexcept { return field_; }
  [[nodiscard]] const std::string& reason() const noexcept { return reason_; }

 private:
  std::string field_, reason_;
};

// How a member's key joins a path: a plain name (letters, digits, '_') always with a dot; any
// other key either quoted, as a JSON string in brackets (a path reads back to one field and
// prints safely: scenarios), or as written (campaigns: the keys of `set` are paths themselves).
enum class KeyJoin : std::uint8_t { kQuoted, kAsWritten };
[[nodiscard]] std::string join_key(const std::string& path, std::string_view key, KeyJoin how = KeyJoin::kQuoted);
// `path` joined with an element: "path[i]".
[[nodiscard]] std::string at_index(const std::string& path, std::size_t i);

// A value as refusals describe it: "an object", "an array", "number 3", "string \"x\"".
[[nodiscard]] std::string describe_json(const nlohmann::json& v);

// Parses `text`, refusing a key written twice in one object (at its path), nesting deeper
// than `max_depth` (at the path of the container that opens level max_depth + 1; before any
// copy or dump, which recurse) and text that is not JSON ("(document)"). Throws JsonRefusal.
[[nodiscard]] nlohmann::json parse_strict_json(std::string_view text, std::size_t max_depth, KeyJoin how);

// Refuses `j` at `path` unless it is an object whose keys are all in `keys`; an unknown key
// is named with the allowed one nearest to it, or with the list. Throws JsonRefusal.
void check_object_keys(const nlohmann::json& j, const std::string& path, std::span<const std::string_view> keys,
                       KeyJoin how);

}  // namespace gyro::sil
