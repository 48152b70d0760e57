// Fuzz target: gyro_sil's scenario parser (apps/scenario.cpp) on arbitrary bytes.
//
// parse_scenario either returns a Scenario or throws ScenarioError naming file, field and
// reason; any other exception, a crash or undefined behaviour is a defect. A refusal names a
// field that exists in the input (its JSON path resolves in the document as far as it
// parses), or, for a missing required field, whose parent object exists and lacks it; or one
// of the pseudo-fields "(document)" (not JSON) and "(root)". An accepted
// scenario must also hold what the parser promises (a positive finite tick, 1..1e8 ticks,
// the schedule in time order, at most kMaxFaultEvents faults). It then goes through the
// configuration check of the stub and the component and of what the run can represent
// (check_configs: ScenarioError or nothing), and, accepted, through the first few ticks of the
// SIL run: a scenario check_configs accepts must run them, without a refusal of the stub
// (RunError) and without a non-finite value in the CSV.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_support.hpp"
#include "scenario.hpp"
#include "sil_runner.hpp"

namespace {

constexpr std::uint64_t kRunTicks = 16;

std::FILE* null_sink() {
  static std::FILE* f = std::fopen("/dev/null", "wb");
  return f;
}

void check_scenario(const gyro::sil::Scenario& s) {
  GYRO_FUZZ_CHECK(s.file == "fuzz.json");
  GYRO_FUZZ_CHECK(s.run.tick_s > 0.0);
  GYRO_FUZZ_CHECK(s.run.ticks >= 1u && s.run.ticks <= 100'000'000u);
  GYRO_FUZZ_CHECK(s.fault_count <= static_cast<std::size_t>(gyro::kMaxFaultEvents));
  for (std::size_t i = 1; i < s.guidance.size(); ++i) {
    GYRO_FUZZ_CHECK(s.guidance[i - 1].t_s <= s.guidance[i].t_s);
    GYRO_FUZZ_CHECK(s.guidance[i - 1].tick <= s.guidance[i].tick);
  }
  for (const gyro::sil::GuidanceEvent& e : s.guidance) {
    GYRO_FUZZ_CHECK(e.t_s >= 0.0 && std::isfinite(e.t_s));
  }
}

using json = nlohmann::json;

// The document as far as the scenario parser reads it: up to the first syntax error or the
// first repeated key (nlohmann's own DOM is lost at a syntax error, and would keep the last of
// repeated keys). A field named by a refusal raised while parsing (a duplicate key, too deep a
// nesting) is in it.
class PartialDom : public nlohmann::json_sax<json> {
 public:
  json root;

  bool null() override { return place(nullptr); }
  bool boolean(bool v) override { return place(v); }
  bool number_integer(number_integer_t v) override { return place(v); }
  bool number_unsigned(number_unsigned_t v) override { return place(v); }
  bool number_float(number_float_t v, const string_t& /*text*/) override { return place(v); }
  bool string(string_t& v) override { return place(v); }
  bool binary(binary_t& v) override { return place(json::binary(v)); }
  bool start_object(std::size_t /*n*/) override { return open(json::object()); }
  bool key(string_t& k) override {
    key_ = k;
    return !open_.back()->contains(k);  // a repeated key: stop there, as the parser does
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t /*n*/) override { return open(json::array()); }
  bool end_array() override { return close(); }
  bool parse_error(std::size_t /*pos*/, const std::string& /*token*/, const nlohmann::detail::exception& /*e*/) override {
    return false;
  }

 private:
  json* put(json v) {
    if (open_.empty()) {
      root = std::move(v);
      return &root;
    }
    json& parent = *open_.back();
    if (parent.is_array()) {
      parent.push_back(std::move(v));
      return &parent.back();
    }
    parent[key_] = std::move(v);
    return &parent[key_];
  }
  bool place(json v) {
    (void)put(std::move(v));
    return true;
  }
  bool open(json v) {
    open_.push_back(put(std::move(v)));  // stable: a container grows only while its child is closed
    return true;
  }
  bool close() {
    open_.pop_back();
    return true;
  }

  std::vector<json*> open_;
  std::string key_;
};

// One step of a field path: ".name", "[3]" or "[\"any key\"]" (a JSON string).
struct Step {
  std::optional<std::string> key;
  std::size_t index{0};
};

std::optional<std::vector<Step>> split_path(std::string_view p) {
  std::vector<Step> steps;
  std::size_t i = 0;
  const auto name_char = [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  };
  while (i < p.size()) {
    if (p[i] == '[' && i + 1 < p.size() && p[i + 1] == '"') {
      std::size_t j = i + 2;
      while (j < p.size() && p[j] != '"') j += p[j] == '\\' ? std::size_t{2} : std::size_t{1};
      if (j + 1 >= p.size() || p[j + 1] != ']') return std::nullopt;
      const json k = json::parse(p.substr(i + 1, j - i), nullptr, false);
      if (!k.is_string()) return std::nullopt;
      steps.push_back({k.get<std::string>(), 0});
      i = j + 2;
    } else if (p[i] == '[') {
      const std::size_t close = p.find(']', i);
      if (close == std::string_view::npos || close == i + 1) return std::nullopt;
      std::size_t n = 0;
      for (std::size_t j = i + 1; j < close; ++j) {
        if (p[j] < '0' || p[j] > '9') return std::nullopt;
        n = n * 10 + static_cast<std::size_t>(p[j] - '0');
      }
      steps.push_back({std::nullopt, n});
      i = close + 1;
    } else {
      if (p[i] == '.') {
        if (steps.empty()) return std::nullopt;
        ++i;
      } else if (!steps.empty()) {
        return std::nullopt;  // a name follows a step only after a dot
      }
      std::size_t j = i;
      while (j < p.size() && name_char(p[j])) ++j;
      if (j == i) return std::nullopt;
      steps.push_back({std::string(p.substr(i, j - i)), 0});
      i = j;
    }
  }
  if (steps.empty()) return std::nullopt;
  return steps;
}

const json* resolve(const json& root, const std::vector<Step>& steps, std::size_t count) {
  const json* at = &root;
  for (std::size_t k = 0; k < count; ++k) {
    const Step& s = steps[k];
    if (s.key) {
      if (!at->is_object()) return nullptr;
      const auto it = at->find(*s.key);
      if (it == at->end()) return nullptr;
      at = &*it;
    } else {
      if (!at->is_array() || s.index >= at->size()) return nullptr;
      at = &(*at)[s.index];
    }
  }
  return at;
}

std::string_view g_input;

void check_error(const gyro::sil::ScenarioError& e) {
  GYRO_FUZZ_CHECK(e.file() == "fuzz.json");
  GYRO_FUZZ_CHECK(!e.field().empty());
  GYRO_FUZZ_CHECK(!e.reason().empty());
  if (e.field() == "(document)" || e.field() == "(root)") return;
  const std::optional<std::vector<Step>> steps = split_path(e.field());
  if (!steps) std::fprintf(stderr, "field: %s\n", e.what());
  GYRO_FUZZ_CHECK(steps.has_value());
  PartialDom dom;
  (void)json::sax_parse(g_input, &dom, json::input_format_t::json, false);
  if (resolve(dom.root, *steps, steps->size()) != nullptr) return;
  // A missing required field: its object exists and lacks it.
  const json* parent = resolve(dom.root, *steps, steps->size() - 1);
  const bool missing = e.reason().rfind("missing required field", 0) == 0 && parent != nullptr &&
                       parent->is_object() && steps->back().key.has_value();
  if (!missing) std::fprintf(stderr, "the refusal names a field not in the input: %s\n", e.what());
  GYRO_FUZZ_CHECK(missing);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  g_input = text;
  gyro::sil::Scenario s;
  try {
    s = gyro::sil::parse_scenario(text, "fuzz.json");
  } catch (const gyro::sil::ScenarioError& e) {
    check_error(e);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "parse_scenario threw %s\n", e.what());
    GYRO_FUZZ_FAIL("parse_scenario threw something other than ScenarioError");
  } catch (...) {
    GYRO_FUZZ_FAIL("parse_scenario threw a non-standard exception");
  }
  check_scenario(s);

  try {
    gyro::sil::check_configs(s);
  } catch (const gyro::sil::ScenarioError& e) {
    check_error(e);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "check_configs threw %s\n", e.what());
    GYRO_FUZZ_FAIL("check_configs threw something other than ScenarioError");
  }

  s.run.ticks = std::min(s.run.ticks, kRunTicks);
  std::FILE* sink = null_sink();
  GYRO_FUZZ_CHECK(sink != nullptr);
  try {
    gyro::sil::CsvWriter csv(sink);
    gyro::sil::RunOptions options;
    options.progress = false;
    const gyro::sil::RunSummary sum = gyro::sil::run_scenario(s, csv, options);
    GYRO_FUZZ_CHECK(sum.rows == s.run.ticks + 1u);
    GYRO_FUZZ_CHECK(sum.nonfinite_values == 0u);
  } catch (const gyro::sil::ScenarioError& e) {
    std::fprintf(stderr, "run_scenario refused what check_configs accepted: %s\n", e.what());
    GYRO_FUZZ_FAIL("a scenario check_configs accepted was refused when run");
  } catch (const gyro::sil::RunError& e) {
    std::fprintf(stderr, "run failed: %s\n", e.what());
    GYRO_FUZZ_FAIL("a scenario check_configs accepted failed in its first ticks");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "run_scenario threw %s\n", e.what());
    GYRO_FUZZ_FAIL("run_scenario threw something other than ScenarioError or RunError");
  }
  return 0;
}
