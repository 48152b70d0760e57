#include "json_path.hpp"

#include <algorithm>
#include <charconv>
#include <limits>

#include "scenario.hpp"

namespace gyro::campaign {

namespace {

using json = nlohmann::json;

bool name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

}  // namespace

std::optional<std::vector<PathStep>> parse_path(std::string_view text, std::string& why) {
  std::vector<PathStep> steps;
  std::size_t i = 0;
  if (text.empty()) {
    why = "empty path";
    return std::nullopt;
  }
  while (i < text.size()) {
    // A member name (required first and after every '.').
    const std::size_t start = i;
    while (i < text.size() && name_char(text[i])) ++i;
    if (i == start) {
      why = "expected a field name at character " + std::to_string(start + 1) + " of \"" + std::string(text) + "\"";
      return std::nullopt;
    }
    steps.push_back(PathStep::member(std::string(text.substr(start, i - start))));
    // Any number of [index].
    while (i < text.size() && text[i] == '[') {
      const std::size_t close = text.find(']', i);
      std::size_t index = 0;
      const char* first = text.data() + i + 1;
      const char* last = close == std::string_view::npos ? first : text.data() + close;
      const std::from_chars_result r = std::from_chars(first, last, index);
      if (close == std::string_view::npos || first == last || r.ptr != last || r.ec != std::errc{}) {
        why = "expected an index [0], [1], ... at character " + std::to_string(i + 1) + " of \"" +
              std::string(text) + "\"";
        return std::nullopt;
      }
      steps.push_back(PathStep::element(index));
      i = close + 1;
    }
    if (i == text.size()) break;
    if (text[i] != '.' || i + 1 == text.size()) {
      why = "unexpected '" + std::string(1, text[i]) + "' at character " + std::to_string(i + 1) + " of \"" +
            std::string(text) + "\"";
      return std::nullopt;
    }
    ++i;
  }
  return steps;
}

std::string format_path(const std::vector<PathStep>& steps) {
  std::string out;
  for (const PathStep& s : steps) {
    if (s.is_element) {
      out += "[" + std::to_string(s.index) + "]";
    } else {
      if (!out.empty()) out += '.';
      out += s.key;
    }
  }
  return out;
}

std::optional<std::string> nearest_name(std::string_view key, const std::vector<std::string>& names) {
  std::size_t best_d = std::numeric_limits<std::size_t>::max();
  const std::string* best = nullptr;
  for (const std::string& n : names) {
    const std::size_t d = sil::edit_distance(key, n);
    if (d < best_d) {
      best_d = d;
      best = &n;
    }
  }
  if (best != nullptr && best_d <= std::max<std::size_t>(2, key.size() / 3)) return *best;
  return std::nullopt;
}

const json* find_path(const json& doc, const std::vector<PathStep>& steps, std::string& why) {
  const json* node = &doc;
  std::vector<PathStep> done;
  for (const PathStep& s : steps) {
    const std::string here = done.empty() ? std::string("the document") : format_path(done);
    if (s.is_element) {
      if (!node->is_array()) {
        why = here + " is " + (node->is_object() ? "an object" : std::string("a ") + node->type_name()) +
              ", not an array";
        return nullptr;
      }
      if (s.index >= node->size()) {
        why = "no element [" + std::to_string(s.index) + "]: " + here + " has " + std::to_string(node->size()) +
              (node->size() == 1 ? " element" : " elements");
        return nullptr;
      }
      node = &(*node)[s.index];
    } else {
      if (!node->is_object()) {
        why = here + " is " + (node->is_array() ? "an array" : std::string("a ") + node->type_name()) +
              ", not an object with a field \"" + s.key + "\"";
        return nullptr;
      }
      const auto it = node->find(s.key);
      if (it == node->end()) {
        std::vector<std::string> names;
        for (const auto& item : node->items()) names.push_back(item.key());
        why = "no field \"" + s.key + "\" in " + here;
        if (const std::optional<std::string> near = nearest_name(s.key, names)) {
          why += " (did you mean \"" + *near + "\"?)";
        } else {
          std::string list;
          for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
          why += " (it has: " + list + ")";
        }
        return nullptr;
      }
      node = &*it;
    }
    done.push_back(s);
  }
  return node;
}

json* find_path(json& doc, const std::vector<PathStep>& steps, std::string& why) {
  return const_cast<json*>(find_path(static_cast<const json&>(doc), steps, why));
}

}  // namespace gyro::campaign
