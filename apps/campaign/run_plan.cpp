#include "run_plan.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>

#include "gyro/noise.hpp"
#include "scenario.hpp"

namespace gyro::campaign {

namespace {

using json = nlohmann::json;

// Truncated normal: rejection from the normal. The campaign refuses windows holding less
// than 1e-3 of the mass, so this bound is never reached in practice (p < e^-100); past it
// the last sample is clamped into the window.
constexpr std::uint64_t kMaxRejections = 100'000;

NoiseStream<double> stream(std::uint64_t seed, std::string_view name) {
  return NoiseStream<double>(seed, fnv1a64(name));
}

double in_interval(const Interval& i, const NoiseStream<double>& s) {
  return i.lo == i.hi ? i.lo : i.lo + (i.hi - i.lo) * s.uniform(0);
}

// Index into cumulative weights for u in [0, 1).
std::size_t pick(const std::vector<double>& cumulative, double u) {
  const double target = u * cumulative.back();
  const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), target);
  return std::min(static_cast<std::size_t>(it - cumulative.begin()), cumulative.size() - 1);
}

double raw_number(const Dispersion& d, const NoiseStream<double>& s) {
  switch (d.distribution) {
    case Distribution::kUniform: return d.min + (d.max - d.min) * s.uniform(0);
    case Distribution::kNormal: return d.mean + d.sd * s.gaussian(0);
    case Distribution::kTruncatedNormal: {
      double x = d.mean;
      for (std::uint64_t i = 0; i < kMaxRejections; ++i) {
        x = d.mean + d.sd * s.gaussian(i);
        if (x >= d.min && x <= d.max) return x;
      }
      return std::clamp(x, d.min, d.max);
    }
    default: return 0;
  }
}

FaultDraw draw_fault(const FaultInjection& fi, std::uint64_t run_index, std::uint64_t seed) {
  FaultDraw f;
  f.option = fi.cycle ? fi.pattern[run_index % fi.pattern.size()]
                      : pick(fi.cumulative_weights, stream(seed, "fault_injection.option").uniform(0));
  const FaultOption& o = fi.options[f.option];
  f.kind = o.kind;
  if (!o.kind) return f;
  f.start_s = in_interval(o.start_s, stream(seed, "fault_injection.start_s"));
  f.duration_s = in_interval(o.duration_s, stream(seed, "fault_injection.duration_s"));
  const double u = stream(seed, "fault_injection.axis").uniform(0);
  f.axis = o.axes[std::min(static_cast<std::size_t>(u * static_cast<double>(o.axes.size())), o.axes.size() - 1)];
  if (o.magnitude) {
    double m = in_interval(*o.magnitude, stream(seed, "fault_injection.magnitude"));
    if (o.either_sign && stream(seed, "fault_injection.sign").uniform(0) < 0.5) m = -m;
    f.magnitude = m;
  }
  return f;
}

}  // namespace

std::uint64_t run_seed(std::uint64_t campaign_seed, std::uint64_t run_index) noexcept {
  return noise_stream_key(campaign_seed, run_index);
}

json draw(const Dispersion& d, const json& base_value, std::uint64_t seed) {
  const NoiseStream<double> s(seed, d.stream);
  json value;
  if (d.distribution == Distribution::kChoice) {
    value = d.values[pick(d.cumulative_weights, s.uniform(0))];
  } else if (d.distribution == Distribution::kUniformInteger) {
    const double n = static_cast<double>(d.int_max) - static_cast<double>(d.int_min) + 1.0;
    const auto offset = static_cast<std::int64_t>(std::floor(s.uniform(0) * n));
    const std::int64_t v = std::min(d.int_min + offset, d.int_max);
    // Non-negative as unsigned, as JSON text reads it (the scenario's counts require that).
    value = v >= 0 ? json(static_cast<std::uint64_t>(v)) : json(v);
  } else {
    value = raw_number(d, s);
  }
  if (d.apply == Apply::kScale) return base_value.get<double>() * value.get<double>();
  if (d.apply == Apply::kOffset) return base_value.get<double>() + value.get<double>();
  return value;
}

RunPlan plan_run(const Campaign& c, std::uint64_t run_index) {
  RunPlan p;
  p.index = run_index;
  p.seed = run_seed(c.seed, run_index);
  p.scenario = c.base;
  for (const Dispersion& d : c.dispersions) {
    std::string why;
    json* node = find_path(p.scenario, d.steps, why);  // checked when the campaign was read
    p.values.push_back(draw(d, *node, p.seed));
    *node = p.values.back();
  }
  if (c.faults) {
    p.fault = draw_fault(*c.faults, run_index, p.seed);
    if (p.fault->kind) {
      json f = {{"kind", gyro::fault_kind_name(*p.fault->kind)},
                {"start_s", p.fault->start_s},
                {"duration_s", p.fault->duration_s},
                {"axis", p.fault->axis}};
      if (p.fault->magnitude) f["magnitude"] = *p.fault->magnitude;
      json& gyro = p.scenario["gyro"];
      if (!gyro.contains("faults")) gyro["faults"] = json::array();
      if (gyro["faults"].is_array()) gyro["faults"].push_back(std::move(f));  // else the scenario refuses it
    }
  }
  p.scenario["gyro"]["seed"] = p.seed;
  return p;
}

}  // namespace gyro::campaign
