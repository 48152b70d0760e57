// Seeded Monte Carlo of SIL runs: every fault kind the stub injects, at random times and
// magnitudes, on gyros dispersed about the base scenario; plus as many fault-free runs.
//
// The residual limit is not guessed: a calibration set of fault-free runs (its own seeds)
// gives the largest residual a healthy dispersed gyro shows, and the limit is that times a
// margin. Detection and false alarms are then measured on independent runs.
//
// Usage: gyro_fault_campaign [base.json] [runs per set] [seed] [--markdown out.md]
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "body_motion.hpp"
#include "gyro/gyro_component.hpp"
#include "gyro/simulated_gyro.hpp"
#include "scenario.hpp"

namespace {

using gyro::FaultKind;
using gyro::GyroMode;
using Vec2 = Eigen::Vector2d;

constexpr double kMargin = 1.5;           // residual limit = margin * calibration maximum
constexpr std::uint64_t kCageTicks = 100;
constexpr std::uint64_t kRunTicks = 1500;
constexpr std::uint64_t kCommandPeriod = 150;  // ticks between new random slew commands
constexpr std::array<FaultKind, 7> kKinds = {
    FaultKind::kStuckPickoff, FaultKind::kInvalidReading,   FaultKind::kDropout,
    FaultKind::kBiasJump,     FaultKind::kDeadTorquer,      FaultKind::kSaturatedTorquer,
    FaultKind::kSpinMotorFailure};

struct RunResult {
  bool fault_mode{false};             // the component went to safe mode at some point
  std::int64_t latency_ticks{-1};     // from fault start to safe mode
  double max_residual{0};             // largest |residual| while free and healthy
};

struct Dispersed {
  gyro::GyroComponentConfig<double> component;
  gyro::SimulatedGyroConfig<double> gyro;
  gyro::sil::BodyProfile body;
  std::uint64_t uncage_tick{};
  std::uint64_t command_seed{};
};

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return lo + (hi - lo) * std::generate_canonical<double, 53>(rng);
}

// The truth (stub) is dispersed about the base scenario; the component keeps the nominal
// configuration, as flight software would.
Dispersed disperse(const gyro::sil::Scenario& base, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Dispersed d{base.component, base.gyro, base.body, 0, 0};
  auto& g = d.gyro;
  g.gyro.pitch_inertia *= uniform(rng, 0.9, 1.1);
  g.gyro.yaw_inertia *= uniform(rng, 0.9, 1.1);
  g.gyro.friction *= uniform(rng, 0.7, 1.3);
  g.spin_hz = uniform(rng, 0.85, 1.15) * base.gyro.spin_hz;
  g.pickoff.noise_rad = uniform(rng, 0.0, 2.0) * base.gyro.pickoff.noise_rad;
  g.pickoff.bias_rad = Vec2(uniform(rng, -3e-4, 3e-4), uniform(rng, -3e-4, 3e-4));
  g.torquer.scale_factor = Vec2(uniform(rng, 0.97, 1.03), uniform(rng, 0.97, 1.03));
  g.seed = seed * 2654435761u + 1u;
  g.faults = {};
  d.body.rate_rad_s = {0.0, uniform(rng, -0.1, 0.1), uniform(rng, -0.1, 0.1)};
  d.body.weave.pitch_amplitude_rad_s = uniform(rng, 0.0, 0.15);
  d.body.weave.yaw_amplitude_rad_s = uniform(rng, 0.0, 0.15);
  d.body.weave.frequency_hz = uniform(rng, 0.5, 3.0);
  d.body.specific_force = {0.0, uniform(rng, -30.0, 30.0), uniform(rng, -30.0, 30.0)};
  d.uncage_tick = kCageTicks;
  d.command_seed = rng();
  return d;
}

void add_fault(Dispersed& d, FaultKind kind, std::uint64_t seed, std::uint64_t& start) {
  std::mt19937_64 rng(seed ^ 0x9e3779b97f4a7c15ull);
  gyro::FaultEvent<double> f;
  f.kind = kind;
  start = 500 + static_cast<std::uint64_t>(uniform(rng, 0.0, 500.0));
  f.start_tick = start;
  f.axis = static_cast<int>(std::floor(uniform(rng, -1.0, 2.0)));
  const double sign = uniform(rng, 0.0, 1.0) < 0.5 ? -1.0 : 1.0;
  switch (kind) {
    case FaultKind::kBiasJump: f.magnitude = sign * uniform(rng, 2e-3, 2e-2); break;
    case FaultKind::kSaturatedTorquer:
      f.magnitude = sign * uniform(rng, 0.2, 1.0) * d.gyro.torquer.max_torque;
      break;
    case FaultKind::kSpinMotorFailure: f.magnitude = uniform(rng, 0.02, 0.3); break;
    default: break;
  }
  if (kind == FaultKind::kSpinMotorFailure) f.axis = -1;
  d.gyro.faults[0] = f;
}

RunResult run_one(const Dispersed& d, std::uint64_t fault_start) {
  RunResult out;
  gyro::SimulatedGyro<double> stub;
  gyro::GyroComponent<double> comp(stub);
  gyro::sil::BodyMotion body(d.body, d.gyro.tick_s);
  if (!stub.configure(d.gyro).ok() || stub.start(body.R_earth_to_body(), Eigen::Vector2d(body.rate_rad_s().tail<2>())) != gyro::Status::kOk ||
      !comp.configure(d.component).ok() || comp.activate() != gyro::Status::kOk) {
    std::fprintf(stderr, "configuration refused\n");
    std::exit(2);
  }
  std::mt19937_64 cmd_rng(d.command_seed);
  gyro::GuidanceInput<double> in;
  in.nav_valid = true;
  for (std::uint64_t k = 1; k <= kRunTicks; ++k) {
    body.advance();
    if (stub.advance(k, body.R_earth_to_body(), Eigen::Vector2d(body.specific_force().tail<2>())) != gyro::Status::kOk) std::exit(3);
    in.R_earth_to_body = body.R_earth_to_body();
    in.body_rate_rad_s = body.rate_rad_s();
    in.request = (k == d.uncage_tick) ? gyro::ModeRequest::kUncage : gyro::ModeRequest::kNone;
    if (k % kCommandPeriod == 0) {
      // Slew around the body's own motion so the gimbals stay inside their cone.
      in.slew_rate_cmd_rad_s = Eigen::Vector2d(body.rate_rad_s().tail<2>()) + Vec2(uniform(cmd_rng, -0.4, 0.4), uniform(cmd_rng, -0.4, 0.4)) -
                               0.5 * comp.telemetry().gimbal_measured_rad / (kCommandPeriod * d.gyro.tick_s);
    }
    (void)comp.step(k, in);
    const auto& tm = comp.telemetry();
    if (comp.mode() == GyroMode::kFault && !out.fault_mode) {
      out.fault_mode = true;
      if (fault_start > 0 && k >= fault_start) out.latency_ticks = static_cast<std::int64_t>(k - fault_start);
    }
    const bool healthy = fault_start == 0 || k < fault_start;
    if (healthy && comp.mode() == GyroMode::kFree) {
      out.max_residual = std::max(out.max_residual, tm.residual_rad.cwiseAbs().maxCoeff());
    }
  }
  return out;
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t i = static_cast<std::size_t>(std::ceil(p * static_cast<double>(v.size()))) - 1;
  return v[std::min(i, v.size() - 1)];
}

}  // namespace

int main(int argc, char** argv) {
  std::string base_path = "scenarios/seeker_slew.json";
  std::size_t runs = 1000;
  std::uint64_t seed = 1;
  std::string markdown;
  std::vector<std::string> pos;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--markdown") == 0 && i + 1 < argc) {
      markdown = argv[++i];
    } else {
      pos.emplace_back(argv[i]);
    }
  }
  if (pos.size() > 0) base_path = pos[0];
  if (pos.size() > 1) runs = std::stoul(pos[1]);
  if (pos.size() > 2) seed = std::stoull(pos[2]);

  gyro::sil::Scenario base;
  try {
    base = gyro::sil::read_scenario(base_path);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  const double tick_ms = base.run.tick_s * 1e3;

  // 1. Calibration: fault-free runs with their own seeds set the residual limit.
  double calib_max = 0;
  const std::size_t calib_runs = std::max<std::size_t>(runs / 2, 1);
  for (std::size_t i = 0; i < calib_runs; ++i) {
    Dispersed d = disperse(base, seed * 1000003u + 7919u * i + 1u);
    d.component.residual_limit_rad = 1.0;  // never trips: measure only
    calib_max = std::max(calib_max, run_one(d, 0).max_residual);
  }
  const double limit = kMargin * calib_max;

  // 2. Fault-free evaluation on independent seeds: false alarms.
  std::size_t false_alarms = 0;
  double eval_max = 0;
  for (std::size_t i = 0; i < runs; ++i) {
    Dispersed d = disperse(base, seed * 2000003u + 104729u * i + 2u);
    d.component.residual_limit_rad = limit;
    const RunResult r = run_one(d, 0);
    false_alarms += r.fault_mode ? 1u : 0u;
    eval_max = std::max(eval_max, r.max_residual);
  }

  // 3. Fault runs: every kind in turn, random start, axis and magnitude.
  std::array<std::vector<double>, kKinds.size()> latencies;
  std::array<std::size_t, kKinds.size()> count{}, detected{}, early{};
  for (std::size_t i = 0; i < runs; ++i) {
    const std::size_t kind = i % kKinds.size();
    const std::uint64_t s = seed * 3000017u + 15485863u * i + 3u;
    Dispersed d = disperse(base, s);
    d.component.residual_limit_rad = limit;
    std::uint64_t start = 0;
    add_fault(d, kKinds[kind], s, start);
    const RunResult r = run_one(d, start);
    ++count[kind];
    if (r.fault_mode && r.latency_ticks < 0) ++early[kind];
    if (r.latency_ticks >= 0) {
      ++detected[kind];
      latencies[kind].push_back(static_cast<double>(r.latency_ticks));
    }
  }

  std::string md;
  char line[512];
  std::snprintf(line, sizeof line,
                "Base scenario `%s`, tick %.3g ms, %zu calibration + %zu fault-free + %zu fault runs, seed %llu.\n\n",
                base_path.c_str(), tick_ms, calib_runs, runs, runs, static_cast<unsigned long long>(seed));
  md += line;
  std::snprintf(line, sizeof line,
                "Residual limit: %.3g x %.3e rad (largest residual of the calibration runs) = **%.3e rad**; "
                "largest residual of the evaluation runs %.3e rad.\n\n",
                kMargin, calib_max, limit, eval_max);
  md += line;
  std::snprintf(line, sizeof line, "False alarms on fault-free runs: **%zu of %zu (%.2f%%)**.\n\n", false_alarms,
                runs, 100.0 * static_cast<double>(false_alarms) / static_cast<double>(runs));
  md += line;
  md += "| fault | runs | detected | rate | latency median | p95 | max | safe mode before the fault |\n";
  md += "|---|---|---|---|---|---|---|---|\n";
  for (std::size_t k = 0; k < kKinds.size(); ++k) {
    const auto& l = latencies[k];
    std::snprintf(line, sizeof line, "| %s | %zu | %zu | %.1f%% | %.1f ms | %.1f ms | %.1f ms | %zu |\n",
                  gyro::to_string(kKinds[k]), count[k], detected[k],
                  100.0 * static_cast<double>(detected[k]) / static_cast<double>(std::max<std::size_t>(count[k], 1)),
                  percentile(l, 0.5) * tick_ms, percentile(l, 0.95) * tick_ms, percentile(l, 1.0) * tick_ms,
                  early[k]);
    md += line;
  }
  std::fputs(md.c_str(), stdout);
  if (!markdown.empty()) {
    std::FILE* f = std::fopen(markdown.c_str(), "w");
    if (!f) {
      std::fprintf(stderr, "cannot write %s\n", markdown.c_str());
      return 1;
    }
    std::fputs(
        "# Fault campaign\n\n"
        "Regenerate with `scripts/fault-campaign.sh` (`tools/fault_campaign.cpp`).\n\n"
        "Method. Every run is the component (nominal configuration of the base scenario) against a\n"
        "SimulatedGyro dispersed about it: J1, J2 +-10%, friction +-30%, spin +-15%, pickoff noise\n"
        "0-2x, bias +-0.3 mrad, torquer scale factor +-3%, body rates +-0.1 rad/s with a weave of up\n"
        "to 0.15 rad/s at 0.5-3 Hz, accelerations +-30 m/s^2, random slew commands every 150 ms.\n"
        "Caged 100 ticks, uncaged, 1,500 ticks in all. Fault runs inject one fault (kinds in turn) at\n"
        "a random tick in [500, 1000) on a random axis, with random magnitude (bias jump 2-20 mrad,\n"
        "saturated torquer 20-100% of full torque, spin motor time constant 20-300 ms), permanent.\n"
        "Latency = ticks from the fault's start to safe mode.\n\n"
        "Thresholds. The residual limit is set from the calibration runs (fault-free, seeds of\n"
        "their own): 1.5 times the largest residual seen while free. Persistence (20 ticks of\n"
        "residual, 10 of rejected readings) and the estimator gain (0.02) were chosen with this\n"
        "tool: with gain 0.05 and 50 ticks, bias jumps below ~5 mrad were absorbed by the estimator\n"
        "before persisting (64% detected); 0.02 and 20 ticks detect 96-98% with no false alarm.\n"
        "The jumps still missed are the smallest, absorbed before they persist: a bias the size of\n"
        "the residual limit cannot be told from a real attitude error by the pickoffs alone.\n\n",
        f);
    std::fputs(md.c_str(), f);
    std::fclose(f);
  }
  return 0;
}
