#include "strict_json.hpp"

#include <set>
#include <vector>

#include "campaign_error.hpp"
#include "json_path.hpp"

namespace gyro::campaign {

namespace {

using json = nlohmann::json;

// The parser's position: one frame per open object or array.
struct Frame {
  bool object{false};
  std::set<std::string> keys;   // seen so far (objects)
  std::string key;              // the current member (objects)
  std::size_t next_index{0};    // of the next element (arrays)
  std::size_t index{0};         // of the current element (arrays)
};

std::string path_of(const std::vector<Frame>& frames) {
  std::vector<PathStep> steps;
  for (const Frame& f : frames) {
    if (f.object) {
      steps.push_back(PathStep::member(f.key));
    } else {
      steps.push_back(PathStep::element(f.index));
    }
  }
  return format_path(steps);
}

}  // namespace

json parse_strict_json(std::string_view text, const std::string& file) {
  std::vector<Frame> frames;
  // Called before a value or a container starts inside an array: its index.
  const auto element_starts = [&frames] {
    if (!frames.empty() && !frames.back().object) frames.back().index = frames.back().next_index++;
  };
  const auto check_depth = [&] {
    if (frames.size() >= kMaxCampaignDepth) {
      throw CampaignError(file, frames.empty() ? "(root)" : path_of(frames),
                          "nested deeper than " + std::to_string(kMaxCampaignDepth) + " levels");
    }
  };
  const json::parser_callback_t callback = [&](int /*depth*/, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
        element_starts();
        check_depth();
        frames.push_back(Frame{true, {}, {}, 0, 0});
        break;
      case json::parse_event_t::array_start:
        element_starts();
        check_depth();
        frames.push_back(Frame{false, {}, {}, 0, 0});
        break;
      case json::parse_event_t::key: {
        Frame& f = frames.back();
        std::string key = parsed.get<std::string>();
        if (!f.keys.insert(key).second) {
          f.key = key;
          throw CampaignError(file, path_of(frames), "duplicate key (written twice in the same object)");
        }
        f.key = std::move(key);
        break;
      }
      case json::parse_event_t::value:
        element_starts();
        break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames.pop_back();
        break;
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
    throw CampaignError(file, "(document)", "not valid JSON: " + what);
  }
}

}  // namespace gyro::campaign
