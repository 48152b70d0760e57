// Campaign JSON -> Campaign, with every refusal naming file, JSON path and reason.
#include "campaign_file.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <map>
#include <vector>

#include "bounded_read.hpp"
#include "scenario_base.hpp"
#include "campaign_error.hpp"
#include "scenario.hpp"
#include "sil_runner.hpp"
#include "strict_json.hpp"

namespace gyro::campaign {

namespace {

using json = nlohmann::json;

// Smallest share of a normal's mass a truncation window may hold (rejection sampling draws
// about 1/share samples per value).
constexpr double kMinTruncatedMass = 1e-3;
constexpr std::uint64_t kMaxWeight = 1'000'000;
constexpr std::size_t kMaxFaultOptions = 64;

std::string number_text(double v) {
  std::array<char, 32> buf{};
  const std::to_chars_result r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return std::string(buf.data(), r.ptr);
}

using sil::at_index;
using sil::describe_json;

// Reads one JSON object of a campaign file (strict_json.hpp), with the campaign's own getters.
class Fields : public sil::StrictObject<CampaignError> {
 public:
  Fields(const std::string& file, const json& j, std::string path, std::initializer_list<const char*> keys)
      : StrictObject(file, j, std::move(path), allowed(keys), sil::KeyJoin::kAsWritten) {}

  // An integer in [lo, hi]: refused with the range when outside, or when not an integer.
  [[nodiscard]] std::uint64_t count(std::string_view key, std::uint64_t lo, std::uint64_t hi) const {
    const json& v = required(key);
    if (v.is_number_unsigned()) {
      const std::uint64_t u = v.get<std::uint64_t>();
      if (u >= lo && u <= hi) return u;
    } else if (!v.is_number_integer()) {
      fail(key, "expected an integer, got " + describe_json(v));
    }
    fail(key, "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + v.dump());
  }
  [[nodiscard]] std::int64_t integer_at(const json& v, const std::string& path) const {
    if (v.is_number_unsigned() && v.get<std::uint64_t>() > static_cast<std::uint64_t>(INT64_MAX)) {
      fail_at(path, "must fit in a signed 64-bit integer, got " + v.dump());
    }
    if (!v.is_number_integer()) fail_at(path, "expected an integer, got " + describe_json(v));
    return v.get<std::int64_t>();
  }
  // A number, or an interval [lo, hi] with lo <= hi.
  [[nodiscard]] Interval interval(std::string_view key) const {
    const json& v = required(key);
    const std::string p = path_of(key);
    if (v.is_array()) {
      if (v.size() != 2) fail(key, "expected a number or an interval [lo, hi], got an array of " +
                                       std::to_string(v.size()));
      Interval i{number_at(v[0], p + "[0]"), number_at(v[1], p + "[1]")};
      if (!(i.lo <= i.hi)) fail(key, "the interval must have lo <= hi, got [" + number_text(i.lo) + ", " +
                                     number_text(i.hi) + "]");
      return i;
    }
    if (!v.is_number()) fail(key, "expected a number or an interval [lo, hi], got " + describe_json(v));
    const double d = number_at(v, p);
    return Interval{d, d};
  }
 private:
  // The allowed keys as views (they outlive the check: string literals).
  [[nodiscard]] static std::vector<std::string_view> allowed(std::initializer_list<const char*> keys) {
    return std::vector<std::string_view>(keys.begin(), keys.end());
  }
};

// The standard normal's CDF.
double phi(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

// ---- base scenario and `set`

json read_json_file(const std::filesystem::path& path, const std::string& refer_as, const std::string& field,
                    const std::string& campaign_file) {
  std::string why;
  const std::optional<std::string> text = sil::read_bounded(path.string(), sil::kMaxScenarioBytes, "a scenario", why);
  if (!text) throw CampaignError(campaign_file, field, "the base scenario \"" + refer_as + "\": " + why);
  return parse_campaign_json(*text, path.string());
}

// The base scenario with its own example or base expanded (scenario_base.hpp).
json resolve_base(const json& base, const std::filesystem::path& dir, const std::string& refer_as,
                  const std::string& campaign_file) {
  try {
    return sil::resolve_scenario_base(base, dir, refer_as);
  } catch (const sil::ScenarioError& e) {
    throw CampaignError(campaign_file, "base", refer_as + ": " + e.field() + ": " + e.reason());
  }
}

bool overlaps(const std::vector<PathStep>& a, const std::vector<PathStep>& b) {
  const std::size_t n = std::min(a.size(), b.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (a[i].is_element != b[i].is_element || a[i].key != b[i].key || a[i].index != b[i].index) return false;
  }
  return true;
}

void apply_set(const Fields& top, json& base) {
  if (!top.has("set")) return;
  const json& set = top.required("set");
  if (!set.is_object()) top.fail("set", "expected an object of \"json.path\": value, got " + describe_json(set));
  std::vector<std::vector<PathStep>> done;
  for (const auto& item : set.items()) {
    const std::string field = top.path_of("set") + "." + item.key();
    std::string why;
    const std::optional<std::vector<PathStep>> steps = parse_path(item.key(), why);
    if (!steps) top.fail_at(field, why);
    for (const std::vector<PathStep>& d : done) {
      if (overlaps(d, *steps)) top.fail_at(field, "overlaps set." + format_path(d));
    }
    json* node = find_path(base, *steps, why);
    if (node == nullptr) {
      // A member may be added to an object that exists (the scenario refuses unknown keys).
      const std::vector<PathStep> parent_steps(steps->begin(), steps->end() - 1);
      std::string parent_why;
      json* parent = steps->back().is_element ? nullptr : find_path(base, parent_steps, parent_why);
      if (parent == nullptr || !parent->is_object()) top.fail_at(field, why + " in the base scenario");
      node = &(*parent)[steps->back().key];
    }
    *node = item.value();
    done.push_back(*steps);
  }
}

// ---- dispersions

Distribution parse_distribution(const Fields& d) {
  const std::string name = d.text("distribution");
  static const std::map<std::string, Distribution> kNames = {
      {"uniform", Distribution::kUniform},
      {"normal", Distribution::kNormal},
      {"truncated_normal", Distribution::kTruncatedNormal},
      {"uniform_integer", Distribution::kUniformInteger},
      {"choice", Distribution::kChoice},
  };
  const auto it = kNames.find(name);
  if (it == kNames.end()) {
    d.fail("distribution",
           "unknown distribution \"" + name + "\" (one of: uniform, normal, truncated_normal, uniform_integer, choice)");
  }
  return it->second;
}

// The keys each distribution takes besides path, distribution and apply.
std::vector<const char*> distribution_keys(Distribution dist) {
  switch (dist) {
    case Distribution::kUniform: return {"min", "max"};
    case Distribution::kNormal: return {"mean", "sd"};
    case Distribution::kTruncatedNormal: return {"mean", "sd", "min", "max"};
    case Distribution::kUniformInteger: return {"min", "max"};
    case Distribution::kChoice: return {"values", "weights"};
  }
  return {};
}

void parse_parameters(const Fields& d, Dispersion& out) {
  // Keys of another distribution are refused by name (a "sd" on a uniform is a mistake).
  for (const char* key : {"min", "max", "mean", "sd", "values", "weights"}) {
    const std::vector<const char*> own = distribution_keys(out.distribution);
    const bool allowed = std::any_of(own.begin(), own.end(), [&](const char* k) { return std::string_view(k) == key; });
    if (!allowed && d.has(key)) {
      d.fail(key, std::string("not a parameter of distribution \"") + to_string(out.distribution) + "\"");
    }
  }
  switch (out.distribution) {
    case Distribution::kUniform:
      out.min = d.number("min");
      out.max = d.number("max");
      if (!(out.min < out.max)) d.fail("max", "must be > min (" + number_text(out.min) + "), got " + number_text(out.max));
      break;
    case Distribution::kNormal:
      out.mean = d.number("mean");
      out.sd = d.number("sd");
      if (!(out.sd > 0)) d.fail("sd", "must be > 0, got " + number_text(out.sd));
      break;
    case Distribution::kTruncatedNormal: {
      out.mean = d.number("mean");
      out.sd = d.number("sd");
      out.min = d.number("min");
      out.max = d.number("max");
      if (!(out.sd > 0)) d.fail("sd", "must be > 0, got " + number_text(out.sd));
      if (!(out.min < out.max)) d.fail("max", "must be > min (" + number_text(out.min) + "), got " + number_text(out.max));
      const double mass = phi((out.max - out.mean) / out.sd) - phi((out.min - out.mean) / out.sd);
      if (!(mass >= kMinTruncatedMass)) {
        d.fail("min", "the window [" + number_text(out.min) + ", " + number_text(out.max) + "] holds a share " +
                          number_text(mass) + " of the normal (mean " + number_text(out.mean) + ", sd " +
                          number_text(out.sd) + "), less than " + number_text(kMinTruncatedMass));
      }
      break;
    }
    case Distribution::kUniformInteger:
      out.int_min = d.integer_at(d.required("min"), d.path_of("min"));
      out.int_max = d.integer_at(d.required("max"), d.path_of("max"));
      if (out.int_min > out.int_max) {
        d.fail("max", "must be >= min (" + std::to_string(out.int_min) + "), got " + std::to_string(out.int_max));
      }
      if (static_cast<double>(out.int_max) - static_cast<double>(out.int_min) > 9007199254740992.0) {
        d.fail("max", "the range must hold at most 2^53 integers");
      }
      break;
    case Distribution::kChoice: {
      const json& values = d.array("values");
      if (values.empty()) d.fail("values", "needs at least one value");
      out.values.assign(values.begin(), values.end());
      std::vector<double> weights(values.size(), 1.0);
      if (d.has("weights")) {
        const json& w = d.array("weights");
        if (w.size() != values.size()) {
          d.fail("weights", "expected " + std::to_string(values.size()) + " weights (one per value), got " +
                                std::to_string(w.size()));
        }
        for (std::size_t i = 0; i < w.size(); ++i) {
          weights[i] = d.number_at(w[i], at_index(d.path_of("weights"), i));
          if (!(weights[i] > 0)) d.fail_at(at_index(d.path_of("weights"), i), "must be > 0, got " + w[i].dump());
        }
      }
      // The running sums must stay finite and grow with every weight: a total that overflows
      // (1e308 + 1e308) or a weight lost in the total's rounding would never be drawn.
      double total = 0;
      for (std::size_t i = 0; i < weights.size(); ++i) {
        const double next = total + weights[i];
        if (!std::isfinite(next)) {
          d.fail("weights", "the weights' total overflows a double at weights[" + std::to_string(i) + "] (" +
                                number_text(weights[i]) + " after a sum of " + number_text(total) + ")");
        }
        if (!(next > total)) {
          d.fail_at(at_index(d.path_of("weights"), i), "too small to change the total " + number_text(total) +
                                                           " of the weights before it: it would never be drawn");
        }
        out.cumulative_weights.push_back(total = next);
      }
      break;
    }
  }
}

Apply parse_apply(const Fields& d) {
  const std::string a = d.text("apply", "set");
  if (a == "set") return Apply::kSet;
  if (a == "scale") return Apply::kScale;
  if (a == "offset") return Apply::kOffset;
  d.fail("apply", "expected \"set\", \"scale\" or \"offset\", got \"" + a + "\"");
}

bool continuous(Distribution d) {
  return d == Distribution::kUniform || d == Distribution::kNormal || d == Distribution::kTruncatedNormal;
}

// The scenario refuses a non-integer at this integer-valued path (a count, a seed, an axis).
bool integer_field(const json& base, const std::vector<PathStep>& steps, const std::string& path) {
  json trial = base;
  std::string why;
  json* node = find_path(trial, steps, why);
  *node = node->get<double>() + 0.5;
  try {
    (void)sil::parse_scenario_document(trial, "trial");
  } catch (const sil::ScenarioError& e) {
    return e.field() == path && e.reason().find("integer") != std::string::npos;
  }
  return false;
}

void check_target(const Fields& d, const json& base, Dispersion& out) {
  std::string why;
  const json* target = find_path(base, out.steps, why);
  if (target == nullptr) d.fail("path", why + " in the base scenario");
  if (out.path == "gyro.seed") {
    d.fail("path", "gyro.seed is the run's seed, set by the campaign from (seed, run index); it is not dispersed");
  }
  const bool numeric_values =
      out.distribution != Distribution::kChoice ||
      std::all_of(out.values.begin(), out.values.end(), [](const json& v) { return v.is_number(); });
  if (out.distribution != Distribution::kChoice && !target->is_number()) {
    d.fail("path", out.path + " is " + describe_json(*target) + ", not a number: only \"choice\" can disperse it");
  }
  if (out.apply != Apply::kSet) {
    if (!target->is_number()) {
      d.fail("apply", std::string("\"") + to_string(out.apply) + "\" needs a number at " + out.path + ", which is " +
                          describe_json(*target));
    }
    if (!numeric_values) d.fail("apply", std::string("\"") + to_string(out.apply) + "\" needs numeric choice values");
  }
  if (continuous(out.distribution) && target->is_number_integer() && integer_field(base, out.steps, out.path)) {
    d.fail("distribution", out.path + " takes an integer: disperse it with \"uniform_integer\" or \"choice\"");
  }
}

Dispersion parse_dispersion(const Fields& d, const json& base) {
  Dispersion out;
  std::string why;
  const std::string text = d.text("path");
  const std::optional<std::vector<PathStep>> steps = parse_path(text, why);
  if (!steps) d.fail("path", why);
  out.steps = *steps;
  out.path = format_path(out.steps);
  out.distribution = parse_distribution(d);
  out.apply = parse_apply(d);
  parse_parameters(d, out);
  check_target(d, base, out);
  out.stream = fnv1a64("dispersion:" + out.path);
  return out;
}

std::vector<Dispersion> parse_dispersions(const Fields& top, const json& base) {
  std::vector<Dispersion> out;
  if (!top.has("dispersions")) return out;
  const json& list = top.array("dispersions");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Fields d(top.file(), list[i], at_index("dispersions", i),
                   {"path", "distribution", "apply", "min", "max", "mean", "sd", "values", "weights"});
    Dispersion disp = parse_dispersion(d, base);
    for (std::size_t j = 0; j < out.size(); ++j) {
      if (overlaps(out[j].steps, disp.steps)) {
        d.fail("path", disp.path + (out[j].path == disp.path ? " is dispersed twice (also " : " overlaps (") +
                           at_index("dispersions", j) + ".path \"" + out[j].path + "\")");
      }
    }
    out.push_back(std::move(disp));
  }
  return out;
}

// ---- fault injection

FaultOption parse_fault_option(const Fields& f, double duration_s) {
  FaultOption o;
  const std::string kind = f.text("kind");
  if (f.has("weight")) o.weight = f.count("weight", 1, kMaxWeight);
  if (kind == "none") {
    for (const char* key : {"start_s", "duration_s", "axis", "magnitude", "sign"}) {
      if (f.has(key)) f.fail(key, "a run without a fault takes no \"" + std::string(key) + "\"");
    }
    return o;
  }
  o.kind = sil::parse_fault_kind(kind);
  if (!o.kind) {
    std::string names = "none";
    for (int k = 1; k < kFaultKindCount; ++k) names += std::string(", ") + gyro::fault_kind_name(static_cast<FaultKind>(k));
    f.fail("kind", "unknown fault kind \"" + kind + "\" (one of: " + names + ")");
  }
  o.start_s = f.interval("start_s");
  if (o.start_s.lo < 0) f.fail("start_s", "must be >= 0, got " + number_text(o.start_s.lo));
  if (o.start_s.hi >= duration_s) {
    f.fail("start_s", "the fault would start at or after the run's end (" + number_text(duration_s) + " s)");
  }
  if (f.has("duration_s")) {
    o.duration_s = f.interval("duration_s");
    if (o.duration_s.lo < 0) f.fail("duration_s", "must be >= 0 (0 = permanent), got " + number_text(o.duration_s.lo));
  }
  if (f.has("axis")) {
    const json& a = f.required("axis");
    const std::string p = f.path_of("axis");
    o.axes.clear();
    const auto one = [&](const json& v, const std::string& path) {
      const std::int64_t axis = f.integer_at(v, path);
      if (axis < -1 || axis > 1) f.fail_at(path, "must be 0 (pitch), 1 (yaw) or -1 (both), got " + v.dump());
      o.axes.push_back(static_cast<int>(axis));
    };
    if (a.is_array()) {
      if (a.empty()) f.fail("axis", "needs at least one axis");
      for (std::size_t i = 0; i < a.size(); ++i) one(a[i], at_index(p, i));
    } else {
      one(a, p);
    }
  }
  if (fault_needs_magnitude(*o.kind)) {
    if (!f.has("magnitude")) {
      f.fail("magnitude", "missing required field (needed by kind \"" + kind + "\")");
    }
    o.magnitude = f.interval("magnitude");
    const std::string sign = f.text("sign", "positive");
    if (sign != "positive" && sign != "either") {
      f.fail("sign", "expected \"positive\" or \"either\", got \"" + sign + "\"");
    }
    o.either_sign = sign == "either";
    if (*o.kind == FaultKind::kSpinMotorFailure && (o.magnitude->lo <= 0 || o.either_sign)) {
      f.fail("magnitude", "the spin's decay time constant must be > 0 (and \"sign\" positive)");
    }
  } else {
    for (const char* key : {"magnitude", "sign"}) {
      if (f.has(key)) f.fail(key, "kind \"" + kind + "\" takes no " + key);
    }
  }
  return o;
}

FaultInjection parse_fault_injection(const Fields& fi, double duration_s, std::size_t base_faults) {
  FaultInjection out;
  const std::string select = fi.text("select", "cycle");
  if (select != "cycle" && select != "random") {
    fi.fail("select", "expected \"cycle\" or \"random\", got \"" + select + "\"");
  }
  out.cycle = select == "cycle";
  const json& list = fi.array("faults");
  if (list.empty()) fi.fail("faults", "needs at least one fault (or {\"kind\": \"none\"})");
  if (list.size() > kMaxFaultOptions) {
    fi.fail("faults", "at most " + std::to_string(kMaxFaultOptions) + " options, got " + std::to_string(list.size()));
  }
  bool any_fault = false;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Fields f(fi.file(), list[i], at_index(fi.path_of("faults"), i),
                   {"kind", "weight", "start_s", "duration_s", "axis", "magnitude", "sign"});
    out.options.push_back(parse_fault_option(f, duration_s));
    any_fault = any_fault || out.options.back().kind.has_value();
  }
  if (any_fault && base_faults >= static_cast<std::size_t>(kMaxFaultEvents)) {
    fi.fail("faults", "the base scenario already has " + std::to_string(base_faults) + " faults, the most a run can have");
  }
  std::uint64_t weights = 0;
  for (const FaultOption& o : out.options) weights += o.weight;  // <= 64 * 10^6: no overflow
  if (weights > kMaxWeightTotal) {
    fi.fail("faults", "the weights total " + std::to_string(weights) + ", more than the limit of " +
                          std::to_string(kMaxWeightTotal));
  }
  double total = 0;
  for (std::size_t i = 0; i < out.options.size(); ++i) {
    for (std::uint64_t w = 0; w < out.options[i].weight; ++w) out.pattern.push_back(i);
    out.cumulative_weights.push_back(total += static_cast<double>(out.options[i].weight));
  }
  return out;
}

// ---- metrics and criteria

std::optional<Window> parse_window(const Fields& m, std::string_view key, double duration_s) {
  if (!m.has(key)) return std::nullopt;
  const json& v = m.required(key);
  if (v.is_boolean()) return v.get<bool>() ? std::optional<Window>(Window{0, duration_s}) : std::nullopt;
  const Fields w(m.file(), v, m.path_of(key), {"from_s", "to_s"});
  Window out{0, duration_s};
  if (w.has("from_s")) out.from_s = w.number("from_s");
  if (w.has("to_s")) out.to_s = w.number("to_s");
  if (out.from_s < 0) w.fail("from_s", "must be >= 0, got " + number_text(out.from_s));
  if (out.to_s > duration_s) w.fail("to_s", "after the run's end (" + number_text(duration_s) + " s)");
  if (!(out.from_s <= out.to_s)) w.fail("to_s", "must be >= from_s (" + number_text(out.from_s) + ")");
  return out;
}

bool flag(const Fields& m, std::string_view key) {
  if (!m.has(key)) return false;
  const json& v = m.required(key);
  if (!v.is_boolean()) m.fail(key, "expected true or false, got " + describe_json(v));
  return v.get<bool>();
}

MetricSet parse_metrics(const Fields& m, double duration_s, bool tracks) {
  MetricSet out;
  out.healthy_residual = flag(m, "healthy_residual");
  out.residual_persistence = flag(m, "residual_persistence");
  out.envelope = flag(m, "envelope");
  out.safe_mode = flag(m, "safe_mode");
  out.slew_rate_error = parse_window(m, "slew_rate_error", duration_s);
  out.pointing_error = parse_window(m, "pointing_error", duration_s);
  out.tracking = parse_window(m, "tracking", duration_s);
  if (out.tracking && !tracks) {
    m.fail("tracking", "the base scenario tracks no line of sight (give it a guidance.track section)");
  }
  out.final_mode = flag(m, "final_mode");
  out.gimbal_stop = flag(m, "gimbal_stop");
  if (m.has("flag_counters")) {
    const json& v = m.required("flag_counters");
    const std::vector<std::string>& names = component_flag_names();
    if (v.is_boolean()) {
      if (v.get<bool>()) {
        for (int i = 0; i < static_cast<int>(names.size()); ++i) out.flag_counters.push_back(i);
      }
    } else if (v.is_array()) {
      for (std::size_t i = 0; i < v.size(); ++i) {
        const std::string p = at_index(m.path_of("flag_counters"), i);
        if (!v[i].is_string()) m.fail_at(p, "expected a flag name, got " + describe_json(v[i]));
        const std::string name = v[i].get<std::string>();
        const auto it = std::find(names.begin(), names.end(), name);
        if (it == names.end()) {
          std::string reason = "unknown flag \"" + name + "\"";
          if (const std::optional<std::string> near = nearest_name(name, names)) reason += " (did you mean \"" + *near + "\"?)";
          m.fail_at(p, reason);
        }
        const int bit = static_cast<int>(it - names.begin());
        if (std::find(out.flag_counters.begin(), out.flag_counters.end(), bit) != out.flag_counters.end()) {
          m.fail_at(p, "flag \"" + name + "\" listed twice");
        }
        out.flag_counters.push_back(bit);
      }
    } else {
      m.fail("flag_counters", "expected true, false or a list of flag names, got " + describe_json(v));
    }
  }
  return out;
}

std::string scope_label(const Criterion& c) {
  switch (c.scope) {
    case RunScope::kAll: return "all runs";
    case RunScope::kFaultFree: return "runs without an injected fault";
    case RunScope::kFaulted: return "runs with an injected fault";
    case RunScope::kKinds: {
      std::string s;
      for (const std::string& k : c.kinds) s += (s.empty() ? "" : ", ") + k;
      return s + " runs";
    }
  }
  return "";
}

Criterion parse_criterion(const Fields& c, const std::vector<MetricColumn>& columns,
                          const std::optional<FaultInjection>& faults) {
  Criterion out;
  out.metric = c.text("metric");
  const auto col = std::find_if(columns.begin(), columns.end(), [&](const MetricColumn& m) { return m.name == out.metric; });
  if (col == columns.end()) {
    std::vector<std::string> names;
    for (const MetricColumn& m : columns) names.push_back(m.name);
    std::string reason = "\"" + out.metric + "\" is not a metric this campaign records";
    if (const std::optional<std::string> near = nearest_name(out.metric, names)) {
      reason += " (did you mean \"" + *near + "\"?)";
    } else {
      std::string list;
      for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
      reason += " (recorded: " + (list.empty() ? std::string("none; enable them under \"metrics\"") : list) + ")";
    }
    c.fail("metric", reason);
  }
  const int ops = (c.has("max") ? 1 : 0) + (c.has("min") ? 1 : 0) + (c.has("equals") ? 1 : 0);
  if (ops != 1) c.fail("max", "give exactly one of \"max\", \"min\" or \"equals\"");
  std::string value_text;
  if (c.has("equals")) {
    out.op = Criterion::Op::kEquals;
    const json& v = c.required("equals");
    switch (col->type) {
      case ColumnType::kNumber: out.number = c.number("equals"); value_text = number_text(out.number); break;
      case ColumnType::kBoolean:
        if (!v.is_boolean()) c.fail("equals", out.metric + " is true or false, got " + describe_json(v));
        out.text = v.get<bool>() ? "true" : "false";
        value_text = out.text;
        break;
      case ColumnType::kMode: {
        if (!v.is_string()) c.fail("equals", out.metric + " is a mode name, got " + describe_json(v));
        out.text = v.get<std::string>();
        GyroMode mode{};
        if (!gyro::enum_from_name(out.text, mode)) {
          std::string names;
          for (const char* n : gyro::enum_names(GyroMode{})) names += (names.empty() ? "" : ", ") + std::string(n);
          c.fail("equals", "unknown mode \"" + out.text + "\" (one of: " + names + ")");
        }
        value_text = out.text;
        break;
      }
      case ColumnType::kCause:
        if (!v.is_string()) c.fail("equals", out.metric + " is a cause such as \"residual\", got " + describe_json(v));
        out.text = v.get<std::string>();
        value_text = out.text;
        break;
    }
  } else {
    const char* key = c.has("max") ? "max" : "min";
    out.op = c.has("max") ? Criterion::Op::kMax : Criterion::Op::kMin;
    if (col->type != ColumnType::kNumber) c.fail(key, out.metric + " is not a number: use \"equals\"");
    out.number = c.number(key);
    value_text = number_text(out.number);
  }
  if (c.has("runs")) {
    const json& r = c.required("runs");
    if (r.is_string()) {
      const std::string s = r.get<std::string>();
      if (s == "all") {
        out.scope = RunScope::kAll;
      } else if (s == "fault_free") {
        out.scope = RunScope::kFaultFree;
      } else if (s == "faulted") {
        out.scope = RunScope::kFaulted;
      } else {
        c.fail("runs", "expected \"all\", \"fault_free\", \"faulted\" or a list of fault kinds, got \"" + s + "\"");
      }
    } else if (r.is_array() && !r.empty()) {
      out.scope = RunScope::kKinds;
      for (std::size_t i = 0; i < r.size(); ++i) {
        const std::string p = at_index(c.path_of("runs"), i);
        if (!r[i].is_string()) c.fail_at(p, "expected a fault kind, got " + describe_json(r[i]));
        const std::string k = r[i].get<std::string>();
        const bool injected = faults && std::any_of(faults->options.begin(), faults->options.end(), [&](const FaultOption& o) {
                                return o.kind ? k == gyro::fault_kind_name(*o.kind) : k == "none";
                              });
        if (!injected) c.fail_at(p, "no run of this campaign injects \"" + k + "\"");
        out.kinds.push_back(k);
      }
    } else {
      c.fail("runs", "expected \"all\", \"fault_free\", \"faulted\" or a non-empty list of fault kinds, got " + describe_json(r));
    }
    if ((out.scope == RunScope::kFaulted || out.scope == RunScope::kFaultFree) && !faults) {
      c.fail("runs", "this campaign injects no faults (\"fault_injection\")");
    }
  }
  const char* op = out.op == Criterion::Op::kMax ? " <= " : out.op == Criterion::Op::kMin ? " >= " : " = ";
  out.label = out.metric + op + value_text + " (" + scope_label(out) + ")";
  return out;
}

// The numeric per-run columns a scatter plot may use: dispersed fields, the fault's draws
// and the numeric metrics.
std::vector<std::string> numeric_columns(const Campaign& c) {
  std::vector<std::string> out;
  if (c.faults) out.insert(out.end(), {"fault_start_s", "fault_duration_s", "fault_magnitude"});
  for (const Dispersion& d : c.dispersions) out.push_back(d.path);
  for (const MetricColumn& m : metric_columns(c.metrics)) {
    if (m.type == ColumnType::kNumber) out.push_back(m.name);
  }
  return out;
}

std::vector<Scatter> parse_plots(const Fields& p, const Campaign& c) {
  std::vector<Scatter> out;
  if (!p.has("scatter")) return out;
  const json& list = p.array("scatter");
  const std::vector<std::string> columns = numeric_columns(c);
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Fields s(p.file(), list[i], at_index(p.path_of("scatter"), i), {"x", "y"});
    Scatter sc{s.text("x"), s.text("y")};
    for (const char* key : {"x", "y"}) {
      const std::string& name = std::string_view(key) == "x" ? sc.x : sc.y;
      if (std::find(columns.begin(), columns.end(), name) != columns.end()) continue;
      std::string reason = "\"" + name + "\" is not a numeric column of this campaign's runs";
      if (const std::optional<std::string> near = nearest_name(name, columns)) reason += " (did you mean \"" + *near + "\"?)";
      s.fail(key, reason);
    }
    out.push_back(std::move(sc));
  }
  return out;
}

}  // namespace

const char* to_string(Distribution d) noexcept {
  switch (d) {
    case Distribution::kUniform: return "uniform";
    case Distribution::kNormal: return "normal";
    case Distribution::kTruncatedNormal: return "truncated_normal";
    case Distribution::kUniformInteger: return "uniform_integer";
    case Distribution::kChoice: return "choice";
  }
  return "unknown";
}

const char* to_string(Apply a) noexcept {
  switch (a) {
    case Apply::kSet: return "set";
    case Apply::kScale: return "scale";
    case Apply::kOffset: return "offset";
  }
  return "unknown";
}

std::uint64_t fnv1a64(std::string_view text) noexcept {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ULL;
  }
  return h;
}

const std::vector<std::string>& component_flag_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (int i = 0; i < kComponentFlagCount; ++i) n.emplace_back(gyro::flag_name(i));
    return n;
  }();
  return names;
}

std::vector<MetricColumn> metric_columns(const MetricSet& m) {
  std::vector<MetricColumn> out;
  if (m.healthy_residual) out.push_back({"max_residual_healthy_rad", ColumnType::kNumber});
  if (m.residual_persistence) out.push_back({"half_limit_persistence_ticks", ColumnType::kNumber});
  if (m.envelope) {
    out.push_back({"max_cone_rad", ColumnType::kNumber});
    out.push_back({"max_gimbal_step_rad", ColumnType::kNumber});
  }
  if (m.safe_mode) {
    out.push_back({"safe_mode_s", ColumnType::kNumber});
    out.push_back({"safe_mode_cause", ColumnType::kCause});
    out.push_back({"detected", ColumnType::kBoolean});
    out.push_back({"false_alarm", ColumnType::kBoolean});
    out.push_back({"safe_mode_after_stop", ColumnType::kBoolean});
    out.push_back({"latency_s", ColumnType::kNumber});
  }
  if (m.slew_rate_error) out.push_back({"slew_rate_error_rad_s", ColumnType::kNumber});
  if (m.pointing_error) out.push_back({"max_pointing_error_rad", ColumnType::kNumber});
  if (m.tracking) {
    out.push_back({"max_track_pointing_error_rad", ColumnType::kNumber});
    out.push_back({"max_los_rate_error_rad_s", ColumnType::kNumber});
  }
  if (m.final_mode) out.push_back({"final_mode", ColumnType::kMode});
  for (int bit : m.flag_counters) {
    out.push_back({"count_" + component_flag_names()[static_cast<std::size_t>(bit)], ColumnType::kNumber});
  }
  if (m.gimbal_stop) {
    out.push_back({"stop_contact_s", ColumnType::kNumber});
    out.push_back({"time_at_stop_s", ColumnType::kNumber});
  }
  return out;
}

namespace {

// "fnv1a64:<16 hex digits>" of the text.
std::string fingerprint_of(std::string_view text) {
  std::array<char, 17> hex{};
  const std::to_chars_result r = std::to_chars(hex.data(), hex.data() + 16, fnv1a64(text), 16);
  return "fnv1a64:" + std::string(16 - static_cast<std::size_t>(r.ptr - hex.data()), '0') + std::string(hex.data(), r.ptr);
}

}  // namespace

Campaign parse_campaign(std::string_view json_text, const std::string& file, const std::filesystem::path& base_dir) {
  json doc = parse_campaign_json(json_text, file);
  Campaign c;
  c.file = file;
  const Fields top(c.file, doc, "",
                   {"description", "base", "set", "runs", "seed", "dispersions", "fault_injection", "metrics", "criteria",
                    "plots"});
  c.description = top.text("description", "");
  // The run count first: nothing is read or allocated for a campaign of too many runs.
  c.runs = top.count("runs", 1, kMaxRuns);

  // The base scenario: inline, or a file relative to the campaign's directory.
  const json& base = top.required("base");
  if (base.is_string()) {
    c.base_source = base.get<std::string>();
    c.base_path = base_dir / c.base_source;
    c.base = resolve_base(read_json_file(*c.base_path, c.base_source, "base", c.file), c.base_path->parent_path(),
                          c.base_source, c.file);
  } else if (base.is_object()) {
    c.base_source = "inline";
    c.base = resolve_base(base, base_dir, "inline", c.file);
  } else {
    top.fail("base", "expected a scenario file's path or a scenario object, got " + describe_json(base));
  }
  json resolved = doc;
  resolved["base"] = c.base;
  apply_set(top, c.base);

  // The base (with `set`) must be a valid scenario by itself.
  sil::Scenario s;
  try {
    s = sil::parse_scenario_document(c.base, "base scenario");
    sil::check_configs(s);
  } catch (const sil::ScenarioError& e) {
    if (c.base_source == "inline") throw CampaignError(c.file, "base." + e.field(), e.reason());
    throw CampaignError(c.file, "base", c.base_source + ": " + e.field() + ": " + e.reason());
  }
  c.tick_s = s.run.tick_s;
  c.ticks = s.run.ticks;
  const double duration_s = static_cast<double>(c.ticks) * c.tick_s;

  c.seed = top.count("seed", 0, std::numeric_limits<std::uint64_t>::max());
  c.dispersions = parse_dispersions(top, c.base);
  if (top.has("fault_injection")) {
    const Fields fi(c.file, top.required("fault_injection"), "fault_injection", {"select", "faults"});
    c.faults = parse_fault_injection(fi, duration_s, s.fault_count);
  }
  if (top.has("metrics")) {
    const Fields m(c.file, top.required("metrics"), "metrics",
                   {"healthy_residual", "residual_persistence", "envelope", "safe_mode", "slew_rate_error",
                    "pointing_error", "tracking", "final_mode", "flag_counters", "gimbal_stop"});
    c.metrics = parse_metrics(m, duration_s, s.track.has_value());
  }
  if (top.has("criteria")) {
    const std::vector<MetricColumn> columns = metric_columns(c.metrics);
    const json& list = top.array("criteria");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const Fields cr(c.file, list[i], at_index("criteria", i), {"metric", "max", "min", "equals", "runs"});
      c.criteria.push_back(parse_criterion(cr, columns, c.faults));
    }
  }

  if (top.has("plots")) c.scatter = parse_plots(Fields(c.file, top.required("plots"), "plots", {"scatter"}), c);

  c.resolved_text = resolved.dump(2) + "\n";
  if (c.resolved_text.size() > kMaxCampaignBytes) {
    top.fail_at("", "with its base scenario inline the campaign has " + std::to_string(c.resolved_text.size()) +
                        " bytes, more than the limit of " + std::to_string(kMaxCampaignBytes) +
                        " bytes for a campaign file (campaign.json must be readable by merge)");
  }
  c.fingerprint = fingerprint_of(c.resolved_text);
  return c;
}

void keep_first_runs(Campaign& c, std::uint64_t n) {
  if (n < 1 || n > c.runs) {
    throw CampaignError(c.file, "runs", "the first " + std::to_string(n) + " runs: expected 1 to the campaign's " +
                                            std::to_string(c.runs));
  }
  json resolved = parse_campaign_json(c.resolved_text, c.file);
  resolved["runs"] = n;
  c.runs = n;
  c.resolved_text = resolved.dump(2) + "\n";
  c.fingerprint = fingerprint_of(c.resolved_text);
}

Campaign read_campaign(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::string why;
  const std::optional<std::string> text = sil::read_bounded(name, kMaxCampaignBytes, "a campaign file", why);
  if (!text) throw CampaignError(name, "(file)", why);
  return parse_campaign(*text, name, path.parent_path());
}

json parse_campaign_json(std::string_view text, const std::string& file) {
  try {
    return sil::parse_strict_json(text, kMaxCampaignDepth, sil::KeyJoin::kAsWritten);
  } catch (const sil::JsonRefusal& r) {
    throw CampaignError(file, r.field(), r.reason());
  }
}

}  // namespace gyro::campaign
