// The strict JSON layer under every file format the tools read (scenarios, campaigns,
// manifests): text -> document refusing what nlohmann::json lets through silently (a key
// written twice, the last one winning), objects checked against their allowed keys, and the
// JSON paths that name a field in every refusal. Each format rethrows a JsonRefusal as its
// own error, with its file name.
#pragma once

#include <cmath>
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

namespace gyro::sil {

// One JSON object of a file, read field by field: its keys are checked against the allowed
// ones up front, then typed fields are handed out; every refusal is an Error(file, JSON path,
// reason) of the file's format (ScenarioError, CampaignError). A format adds its own getters
// by deriving from it.
template <class Error>
class StrictObject {
 public:
  StrictObject(const std::string& file, const nlohmann::json& j, std::string path,
               std::span<const std::string_view> keys, KeyJoin how)
      : file_(file), j_(j), path_(std::move(path)), how_(how) {
    try {
      check_object_keys(j, path_, keys, how_);
    } catch (const JsonRefusal& r) {
      throw Error(file_, r.field(), r.reason());
    }
  }

  [[nodiscard]] const std::string& file() const noexcept { return file_; }
  [[nodiscard]] const std::string& path() const noexcept { return path_; }
  [[nodiscard]] std::string path_of(std::string_view key) const { return join_key(path_, key, how_); }
  [[nodiscard]] bool has(std::string_view key) const { return j_.contains(key); }

  [[noreturn]] void fail(std::string_view key, const std::string& reason) const { fail_at(path_of(key), reason); }
  [[noreturn]] void fail_at(const std::string& path, const std::string& reason) const {
    throw Error(file_, path.empty() ? "(root)" : path, reason);
  }

  [[nodiscard]] const nlohmann::json& required(std::string_view key) const {
    const auto it = j_.find(key);
    if (it == j_.end()) fail(key, "missing required field");
    return *it;
  }

  [[nodiscard]] double number(std::string_view key) const { return number_at(required(key), path_of(key)); }
  [[nodiscard]] double number(std::string_view key, double fallback) const {
    return has(key) ? number(key) : fallback;
  }
  // A finite number at `path` (an element of an array, say).
  [[nodiscard]] double number_at(const nlohmann::json& v, const std::string& path) const {
    if (!v.is_number()) fail_at(path, "expected a number, got " + describe_json(v));
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail_at(path, "not a finite number");
    return d;
  }

  [[nodiscard]] bool boolean(std::string_view key) const {
    const nlohmann::json& v = required(key);
    if (!v.is_boolean()) fail(key, "expected true or false, got " + describe_json(v));
    return v.get<bool>();
  }
  [[nodiscard]] bool boolean(std::string_view key, bool fallback) const { return has(key) ? boolean(key) : fallback; }

  [[nodiscard]] std::string text(std::string_view key) const {
    const nlohmann::json& v = required(key);
    if (!v.is_string()) fail(key, "expected a string, got " + describe_json(v));
    return v.get<std::string>();
  }
  [[nodiscard]] std::string text(std::string_view key, const std::string& fallback) const {
    return has(key) ? text(key) : fallback;
  }

  [[nodiscard]] const nlohmann::json& array(std::string_view key) const {
    const nlohmann::json& v = required(key);
    if (!v.is_array()) fail(key, "expected an array, got " + describe_json(v));
    return v;
  }

 private:
  const std::string& file_;
  const nlohmann::json& j_;
  std::string path_;
  KeyJoin how_;
};

}  // namespace gyro::sil
