// Soak: a long flight of the component against the stub (default 1e8 ticks, 1,000 flights of
// 1e5 ticks back to back). Checks that nothing drifts or overflows: time stays an integer
// tick count, counters saturate instead of wrapping, the attitude stays a rotation, the
// residual stays bounded, no fault, and the process's memory stays flat.
//
// Usage: gyro_soak [base.json] [ticks]
#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <fstream>
#include <malloc.h>
#include <string>

#include "body_motion.hpp"
#include "gyro/gyro_component.hpp"
#include "gyro/sil_loop.hpp"
#include "gyro/simulated_gyro.hpp"
#include "scenario.hpp"

namespace {

long resident_kib() {
  std::ifstream status("/proc/self/status");
  std::string key;
  long value = -1;
  while (status >> key) {
    if (key == "VmRSS:") {
      status >> value;
      break;
    }
  }
  return value;
}

// Bytes the heap has handed out and not taken back.
std::size_t heap_in_use() { return mallinfo2().uordblks; }

}  // namespace

int main(int argc, char** argv) {
  const std::string base_path = argc > 1 ? argv[1] : "scenarios/seeker_slew.json";
  const std::uint64_t ticks = argc > 2 ? std::stoull(argv[2]) : 100'000'000ull;
  gyro::sil::Scenario s;
  try {
    s = gyro::sil::read_scenario(base_path);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  s.gyro.faults = {};
  s.body.rate_rad_s = {0.0, 0.0, 0.0};  // the body weaves about a fixed mean attitude
  gyro::SimulatedGyro<double> stub;
  gyro::GyroComponent<double> comp(stub);
  // The stub sees the body as the report's driver gives it (attitude, lateral and normal force).
  gyro::SilLoop<double, gyro::GyroComponent<double>> loop(stub, comp, gyro::StubBodyFeed::kAttitude);
  gyro::sil::BodyMotion body(s.body, s.run.tick_s);
  const auto sample = [&body] {
    gyro::BodySample<double> b;
    b.R_earth_to_body = body.R_earth_to_body();
    b.rate_rad_s = body.rate_rad_s();
    b.specific_force = body.specific_force();
    return b;
  };
  bool configured = stub.configure(s.gyro).ok() && comp.configure(s.component).ok();
  if (configured) {
    const gyro::SilStatus<gyro::Status> started = loop.start(sample());
    configured = started.stub == gyro::Status::kOk && started.component == gyro::Status::kOk;
  }
  if (!configured) {
    std::fprintf(stderr, "configuration refused\n");
    return 2;
  }
  gyro::GuidanceCommand<double> command;
  const long rss_start = resident_kib();
  long rss_after_warmup = -1;
  std::size_t heap_after_warmup = 0;
  double worst_residual = 0, worst_ortho_est = 0, worst_ortho_truth = 0;
  std::uint64_t faults = 0;
  float t_accumulated = 0.0f;  // what a float clock summing ticks would read
  const float tick_f = static_cast<float>(s.run.tick_s);
  const std::uint64_t report_every = std::max<std::uint64_t>(ticks / 10, 1);
  for (std::uint64_t k = 1; k <= ticks; ++k) {
    body.advance();
    t_accumulated += tick_f;
    command.request = (k == 100) ? gyro::ModeRequest::kUncage : gyro::ModeRequest::kNone;
    // Track the body, closing the gimbal angles slowly: the seeker holds its line of sight.
    command.slew_rate_cmd_rad_s =
        Eigen::Vector2d(body.rate_rad_s().tail<2>()) - 2.0 * comp.telemetry().gimbal_measured_rad;
    const gyro::SilStatus<gyro::Status> ran = loop.tick(k, sample(), command);
    if (ran.stub != gyro::Status::kOk) {
      std::fprintf(stderr, "stub refused tick %" PRIu64 "\n", k);
      return 1;
    }
    if (ran.component != gyro::Status::kOk) {
      std::fprintf(stderr, "component refused tick %" PRIu64 "\n", k);
      return 1;
    }
    const auto& tm = comp.telemetry();
    if (comp.mode() == gyro::GyroMode::kFault) ++faults;
    if (comp.mode() == gyro::GyroMode::kFree) {
      worst_residual = std::max(worst_residual, tm.residual_rad.cwiseAbs().maxCoeff());
    }
    if (k == std::min<std::uint64_t>(1'000'000, ticks)) {
      rss_after_warmup = resident_kib();
      heap_after_warmup = heap_in_use();
    }
    if (k % report_every == 0 || k == ticks) {
      const Eigen::Matrix3d r_est = tm.attitude_gyro_to_earth.toRotationMatrix();
      worst_ortho_est = std::max(worst_ortho_est, gyro::orthonormality_error(r_est));
      if (const gyro::GyroModel<double>* m = stub.report_model()) {
        worst_ortho_truth = std::max(worst_ortho_truth, gyro::orthonormality_error(m->R_earth_to_gyro()));
      }
      std::fprintf(stderr, "tick %" PRIu64 " (t = %.0f s): mode %s, residual max %.3e rad, RSS %ld KiB\n", k,
                   static_cast<double>(k) * s.run.tick_s, gyro::enum_name(comp.mode()), worst_residual,
                   resident_kib());
    }
  }
  const auto& tm = comp.telemetry();
  const long rss_end = resident_kib();
  const std::size_t heap_end = heap_in_use();
  const double t_end = static_cast<double>(tm.tick) * s.run.tick_s;
  std::printf("ticks                   %" PRIu64 " (telemetry tick %" PRIu64 ", t = %.3f s)\n", ticks, tm.tick, t_end);
  std::printf("time at end             exact (integer ticks); a float clock summing the tick reads %.6g s "
              "(error %.3g s)\n",
              static_cast<double>(t_accumulated), static_cast<double>(t_accumulated) - t_end);
  std::printf("fault ticks             %" PRIu64 "\n", faults);
  std::printf("worst residual (free)   %.3e rad\n", worst_residual);
  std::printf("orthonormality          estimator %.3e, truth %.3e\n", worst_ortho_est, worst_ortho_truth);
  std::printf("counters                invalid %u, stale %u, jump %u, saturated %u, unresolved %u\n",
              tm.counters[3], tm.counters[4], tm.counters[5], tm.counters[7], tm.counters[2]);
  std::printf("memory (VmRSS)          start %ld KiB, after 1e6 ticks %ld KiB, end %ld KiB\n", rss_start,
              rss_after_warmup, rss_end);
  std::printf("heap in use             after 1e6 ticks %zu B, end %zu B\n", heap_after_warmup, heap_end);
  const bool ok = faults == 0 && tm.tick == ticks && worst_ortho_est < 1e-12 && worst_ortho_truth < 1e-12 &&
                  heap_end == heap_after_warmup && rss_end <= rss_after_warmup + 1024;
  // (RSS moves by a few pages as stdio and libm pages are touched; the heap must not move.)
  std::printf("%s\n", ok ? "soak passed" : "soak FAILED");
  return ok ? 0 : 1;
}
