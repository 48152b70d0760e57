// The docs' configuration tables, generated from the field tables (gyro/config_fields.hpp) so
// that they cannot drift: unit, default, range and rule of every field. gyro_config_doc
// writes them into docs/ between the markers
//
//   <!-- generated: NAME (gyro_config_doc) -->  ...  <!-- end generated: NAME -->
//
// and config_fields_test checks that the committed docs hold what it would write.
#pragma once

#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "gyro/component_types.hpp"
#include "gyro/simulated_gyro.hpp"
#include "scenario_defaults.hpp"

namespace gyro::doc {

inline std::string number(double v) {
  if (v == 1.5707963267948966) return "pi/2";
  if (v == 3.141592653589793) return "pi";
  std::array<char, 32> buf{};
  const std::to_chars_result r = std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::general, 6);
  return std::string(buf.data(), r.ptr);
}

template <class M>
std::string default_text(const Field& f, const M& m) {
  if (f.presence == Presence::kRequired) return "required";
  if constexpr (std::is_same_v<M, bool>) {
    return m ? "true" : "false";
  } else if constexpr (kHasEnumNames<M>) {
    const char* name = enum_name(m);
    return name != nullptr ? std::string("`\"") + name + "\"`" : "";
  } else if constexpr (std::is_arithmetic_v<M>) {
    return number(static_cast<double>(m));
  } else if constexpr (std::is_base_of_v<Eigen::EigenBase<M>, M>) {
    std::string s = "[";
    for (Eigen::Index i = 0; i < m.size(); ++i) s += (i ? ", " : "") + number(static_cast<double>(m(i)));
    return s + "]";
  } else {
    return "";
  }
}

template <class M>
std::string range_text(const Field& f, const M&) {
  if constexpr (std::is_same_v<M, bool>) {
    return "true, false";
  } else if constexpr (kHasEnumNames<M>) {
    constexpr auto names = enum_names(M{});
    std::string s;
    for (std::size_t i = 0; i < names.size(); ++i) s += std::string(i ? ", " : "") + "`\"" + names[i] + "\"`";
    return s;
  } else {
    if (!std::isfinite(f.lower) && !std::isfinite(f.upper)) return f.rule == Rule::kNone ? "any" : "finite";
    const bool open = f.rule == Rule::kPositive && !(f.lower > 0.0);
    return std::string(open ? "(" : "[") + number(f.lower) + ", " + number(f.upper) + "]";
  }
}

// One table: a row per field given in files (implied fields are set from elsewhere), with the
// key as a file spells it (its section, then its name after `strip`). `defaults` holds what a
// file left out gets; `default_notes` replaces that text for a field whose default is no
// number (another field's value), by name.
template <class Config>
std::string table(const Config& defaults, const std::string& strip = "",
                  const std::map<std::string, std::string>& default_notes = {}) {
  std::ostringstream out;
  out << "| key | unit | default | range | rule |\n|---|---|---|---|---|\n";
  visit_fields(
      [&](const Field& f, const auto& m) {
        using M = std::decay_t<decltype(m)>;
        if (f.presence == Presence::kImplied) return;
        if constexpr (kHasFieldTable<M>) {
          return;  // a nested struct: its own table
        } else {
          std::string name = f.name;
          if (!strip.empty() && name.rfind(strip, 0) == 0) name = name.substr(strip.size());
          const std::string key = (f.section ? std::string(f.section) + "." : "") + name;
          const auto note = default_notes.find(f.name);
          out << "| `" << key << "` | " << (f.unit && *f.unit ? f.unit : "–") << " | "
              << (note != default_notes.end() ? note->second : default_text(f, m)) << " | " << range_text(f, m)
              << " | " << (f.why ? f.why : "") << " |\n";
        }
      },
      defaults);
  return out.str();
}

// The defaults a scenario gives (apps/scenario_defaults.hpp).
inline SimulatedGyroConfig<double> scenario_gyro() {
  SimulatedGyroConfig<double> c{};
  c.seed = sil::kScenarioSeed;
  return c;
}
inline GimbalPlantConfig<double> scenario_gimbal() {
  GimbalPlantConfig<double> g{};
  sil::set_scenario_envelope(g);
  return g;
}

// The generated tables, by marker name.
struct Generated {
  std::string file;  // under docs/
  std::string name;
  std::string text;
};

inline std::vector<Generated> generated_tables() {
  return {
      {"scenarios.md", "component fields", table(GyroComponentConfig<double>{})},
      {"scenarios.md", "stub fields", table(scenario_gyro())},
      {"scenarios.md", "model fields", table(GyroModelConfig<double>{})},
      {"scenarios.md", "error source fields", table(AxisErrorSources<double>{})},
      {"scenarios.md", "gimbal plant fields",
       table(scenario_gimbal(), "",
             {{"inner_friction", "`rotor.friction`"},
              {"outer_friction", "`rotor.friction`"},
              {"motor_torque_limit", "none: to be given with `spin_drive` `\"motor\"`"}})},
      {"scenarios.md", "pickoff fields", table(PickoffModel<double>{})},
      {"scenarios.md", "torquer fields", table(TorquerModel<double>{})},
      {"component.md", "component fields", table(GyroComponentConfig<double>{})},
  };
}

inline std::string begin_marker(const std::string& name) { return "<!-- generated: " + name + " (gyro_config_doc) -->"; }
inline std::string end_marker(const std::string& name) { return "<!-- end generated: " + name + " -->"; }

// `text` with the table between the markers of `name` replaced by `table`; false if there are
// no markers.
inline bool replace_between(std::string& text, const std::string& name, const std::string& table) {
  const std::string b = begin_marker(name), e = end_marker(name);
  const std::size_t p = text.find(b);
  if (p == std::string::npos) return false;
  const std::size_t q = text.find(e, p);
  if (q == std::string::npos) return false;
  text.replace(p + b.size(), q - p - b.size(), "\n" + table);
  return true;
}

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace gyro::doc
