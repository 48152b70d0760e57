#include "scenario_base.hpp"

#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "bounded_read.hpp"
#include "gyro/report_sample.hpp"
#include "gyro/seeker_example.hpp"
#include "scenario.hpp"
#include "scenario_defaults.hpp"
#include "strict_json.hpp"

namespace gyro::sil {

namespace {

using json = nlohmann::json;

// A section's configuration as it reads back: what a key left out must not change.
using Reread = std::function<json(const json&)>;

std::optional<json> reread(const Reread& read, const json& section) {
  try {
    return read(section);
  } catch (const ScenarioError&) {
    return std::nullopt;  // a required field left out
  }
}

// Every key of `node` (depth first, members of objects; arrays are values) whose removal from
// `section` leaves it reading back as `meant`, removed.
void drop_defaults(json& section, json& node, const Reread& read, const json& meant) {
  std::vector<std::string> keys;
  for (const auto& item : node.items()) keys.push_back(item.key());
  for (const std::string& key : keys) {
    if (node[key].is_object()) drop_defaults(section, node[key], read, meant);
    json removed = std::move(node[key]);
    node.erase(key);
    if (reread(read, section) != meant) node[key] = std::move(removed);
  }
}

json shortest(json section, const Reread& read) {
  const std::optional<json> meant = reread(read, section);
  if (meant) drop_defaults(section, section, read, *meant);
  return section;
}

json gyro_form(const SimulatedGyroConfig<double>& c) {
  const double tick = c.tick_s;
  return shortest(gyro_section(c, 0), [tick](const json& g) {
    return gyro_section(parse_gyro_section(g, tick, "example", "gyro").gyro, 0);
  });
}

json component_form(const GyroComponentConfig<double>& c) {
  const double tick = c.tick_s;
  return shortest(component_section(c), [tick](const json& g) {
    return component_section(parse_component_section(g, tick, "example", "component").component);
  });
}

json seeker() {
  using S = SeekerExample<double>;
  return {{"gyro", gyro_form(S::stub())}, {"component", component_form(S::component())}};
}

// The report defines its rotor and the model's limits, not a flight configuration.
json report() {
  using R = ReportSample<double>;
  SimulatedGyroConfig<double> c;
  c.plant = PlantKind::kReport;
  c.gyro = R::config();
  c.spin_hz = R::kSpinHz;
  c.tick_s = R::initg_step();
  c.seed = kScenarioSeed;
  return {{"gyro", gyro_form(c)}};
}

struct Example {
  std::string_view name;
  json (*sections)();
};

constexpr Example kExamples[] = {{"seeker", seeker}, {"report", report}};

json read_base(const std::filesystem::path& path, const std::string& file) {
  std::string why;
  const std::optional<std::string> text = read_bounded(path.string(), kMaxScenarioBytes, "a scenario", why);
  if (!text) throw ScenarioError(file, "base", "\"" + path.string() + "\": " + why);
  try {
    return parse_strict_json(*text, kMaxJsonDepth, KeyJoin::kQuoted);
  } catch (const JsonRefusal& r) {
    throw ScenarioError(file, "base", "\"" + path.string() + "\": " + r.field() + ": " + r.reason());
  }
}

json resolve(const json& doc, const std::filesystem::path& dir, const std::string& file, std::size_t depth) {
  if (!doc.is_object()) return doc;
  const bool has_example = doc.contains("example");
  const bool has_base = doc.contains("base");
  if (!has_example && !has_base) return doc;
  if (has_example && has_base) {
    throw ScenarioError(file, "base", "a scenario builds on an example or on a base scenario, not both");
  }
  const char* key = has_example ? "example" : "base";
  const json& name = doc.at(key);
  if (!name.is_string()) {
    throw ScenarioError(file, key, std::string("expected a string, got ") + name.type_name());
  }
  json under;
  if (has_example) {
    under = example_sections(name.get<std::string>(), file);
  } else {
    if (depth >= kMaxScenarioBases) {
      throw ScenarioError(file, "base",
                          "more than " + std::to_string(kMaxScenarioBases) + " bases in a chain (or a cycle)");
    }
    const std::filesystem::path path = dir / name.get<std::string>();
    const std::string base_file = path.string();
    under = resolve(read_base(path, file), path.parent_path(), base_file, depth + 1);
  }
  json patch = doc;
  patch.erase(key);
  under.merge_patch(patch);
  return under;
}

}  // namespace

json example_sections(std::string_view name, const std::string& file) {
  for (const Example& e : kExamples) {
    if (e.name == name) return e.sections();
  }
  throw ScenarioError(file, "example", "unknown example \"" + std::string(name) + "\" (one of: " + example_names() + ")");
}

std::string example_names() {
  std::string out;
  for (const Example& e : kExamples) out += (out.empty() ? "" : ", ") + std::string(e.name);
  return out;
}

json resolve_scenario_base(const json& doc, const std::filesystem::path& dir, const std::string& file) {
  return resolve(doc, dir, file, 0);
}

}  // namespace gyro::sil
