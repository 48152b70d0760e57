#include "strict_json.hpp"

#include <algorithm>
#include <limits>
#include <set>
#include <vector>

#include "scenario.hpp"

namespace gyro::sil {

namespace {

using json = nlohmann::json;

bool plain_key(std::string_view key) {
  return !key.empty() && std::all_of(key.begin(), key.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  });
}

std::string field_or_root(const std::string& path) { return path.empty() ? "(root)" : path; }

std::string quoted_list(std::span<const std::string_view> names) {
  std::string out;
  for (std::string_view n : names) {
    if (!out.empty()) out += ", ";
    out += '"';
    out += n;
    out += '"';
  }
  return out;
}

// The parser's position: one frame per open object or array.
struct Frame {
  std::string path;
  bool array{false};
  std::size_t index{0};         // of the next element (arrays)
  std::string key;              // the current member (objects)
  std::set<std::string> keys;   // seen so far (objects)
};

}  // namespace

std::string join_key(const std::string& path, std::string_view key, KeyJoin how) {
  std::string out = path;
  // An empty key is quoted either way: written as is it would name no field.
  if ((how == KeyJoin::kAsWritten && !key.empty()) || plain_key(key)) {
    if (!out.empty()) out += '.';
    out += key;
  } else {
    out += '[';
    out += json(std::string(key)).dump(-1, ' ', true);  // ASCII only: every other character as \uXXXX
    out += ']';
  }
  return out;
}

std::string at_index(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

std::string describe_json(const json& v) {
  if (v.is_object()) return "an object";
  if (v.is_array()) return "an array";
  return std::string(v.type_name()) + " " + v.dump();
}

json parse_strict_json(std::string_view text, std::size_t max_depth, KeyJoin how) {
  std::vector<Frame> frames;
  const auto element_done = [&frames] {
    if (!frames.empty() && frames.back().array) ++frames.back().index;
  };
  const auto open = [&](bool array) {
    std::string path;
    if (!frames.empty()) {
      const Frame& parent = frames.back();
      path = parent.array ? at_index(parent.path, parent.index) : join_key(parent.path, parent.key, how);
    }
    if (frames.size() >= max_depth) {
      throw JsonRefusal(field_or_root(path), "nested deeper than " + std::to_string(max_depth) + " levels");
    }
    frames.push_back(Frame{std::move(path), array, 0, {}, {}});
  };
  const json::parser_callback_t callback = [&](int /*depth*/, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start: open(false); break;
      case json::parse_event_t::array_start: open(true); break;
      case json::parse_event_t::key: {
        Frame& f = frames.back();
        const std::string& k = parsed.get_ref<const std::string&>();
        if (!f.keys.insert(k).second) {
          throw JsonRefusal(join_key(f.path, k, how), "duplicate key (a key may appear only once in an object)");
        }
        f.key = k;
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames.pop_back();
        element_done();
        break;
      case json::parse_event_t::value: element_done(); break;
    }
    return true;
  };
  try {
    return json::parse(text.begin(), text.end(), callback, true, false);
  } catch (const json::exception& e) {
    std::string what = e.what();
    if (!what.empty() && what.front() == '[') {
      const std::size_t close = what.find("] ");
      if (close != std::string::npos) what.erase(0, close + 2);
    }
    throw JsonRefusal("(document)", "not valid JSON: " + what);
  }
}

void check_object_keys(const json& j, const std::string& path, std::span<const std::string_view> keys, KeyJoin how) {
  if (!j.is_object()) throw JsonRefusal(field_or_root(path), "expected an object, got " + describe_json(j));
  for (const auto& item : j.items()) {
    const std::string& k = item.key();
    if (std::find(keys.begin(), keys.end(), k) != keys.end()) continue;
    std::string reason = "unknown key";
    std::string_view best;
    std::size_t best_d = std::numeric_limits<std::size_t>::max();
    for (std::string_view allowed : keys) {
      const std::size_t d = edit_distance(k, allowed);
      if (d < best_d) {
        best_d = d;
        best = allowed;
      }
    }
    if (!best.empty() && best_d <= std::max<std::size_t>(2, k.size() / 3)) {
      reason += " (did you mean \"" + std::string(best) + "\"?)";
    } else {
      reason += " (allowed: " + quoted_list(keys) + ")";
    }
    throw JsonRefusal(join_key(path, k, how), reason);
  }
}

}  // namespace gyro::sil
