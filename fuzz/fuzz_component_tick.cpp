// Fuzz target: GyroComponent over a port whose every answer comes from the fuzz bytes, with
// guidance inputs from the fuzz bytes, for up to kMaxTicks ticks; float or double.
//
// Input: byte 0 (bit 0 float; bit 1 overrides configuration fields; bit 2 steps before
// activation; bit 3 friction_compensation off; bit 4 use_spin_readback off); with bit 1 a
// 32-bit field mask (bit i: the i-th number or count of the configuration's field table) and
// the overriding values; then one operation word (16 bits) per tick.
// Each bit of the word changes one thing for that tick (see Script::next): the pickoff angles,
// the sequence counter, the valid bits and spin readback, a port failure on read or on write,
// the mode request (invalid enum values included), the slew command, the navigation (valid
// bit, attitude including non-rotations, body rates), the tick number (repeats, gaps, going
// back), calls of configure()/activate() while active, and a repeat count for the tick.
// Values are Bytes::value: NaN, infinities, denormals, extremes and raw bits included.
//
// Invariants, after every call:
//   - telemetry's floating fields are all finite, its attitude quaternion a unit one;
//   - counters never decrease: each grows by one exactly when its flag is raised (saturating);
//   - before activate(), step() is refused with kNotActive counted, no port traffic;
//   - once active, no input stops a tick (docs/component.md, "Corrupt input"): every call
//     reads the pickoffs once and writes the torquer once, and returns kOk, or kInputIgnored
//     exactly when a field was unusable (a non-finite slew command, an unknown request,
//     navigation marked valid but unusable, a tick count that repeats, goes back, jumps
//     beyond max_tick_gap or follows an untrusted count), with the matching flags;
//   - the mode changes only as docs/component.md allows (idle->caged only by activate();
//     caged->uncaging on an uncage request with an accepted reading and usable navigation;
//     uncaging->free after uncage_settle_ticks ticks; uncaging/free->caged on a cage request;
//     any active mode->fault; fault->caged on a cage request; nothing else; an unknown
//     request is no request);
//   - the torque written is finite and within max_torque; zero in fault, and when uncaging
//     without stop protection once the torque shaper has emptied;
//     kFaultLatched is raised exactly in fault;
//   - a twin component handed the same calls and port answers publishes bit-identical
//     telemetry and writes bit-identical torques (deterministic, nothing uninitialised);
//   - configure() and activate() are refused once active and change nothing.
#include <array>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "fuzz_support.hpp"
#include "gyro/gyro_component.hpp"
#include "gyro/seeker_example.hpp"

namespace {

using gyro::ComponentFlag;
using gyro::GyroMode;
using gyro::ModeRequest;
using gyro::PortStatus;
using gyro::Status;
using gyro::fuzz::Bytes;
using gyro::fuzz::finite_coeffs;
using gyro::fuzz::same_bits;
using gyro::fuzz::same_scalar_bits;

constexpr int kMaxTicks = 400;

// What the port answers in one tick.
template <typename T>
struct PortScript {
  PortStatus read_status{PortStatus::kOk};
  gyro::PickoffReading<T> reading{};
  PortStatus write_status{PortStatus::kOk};
};

// The fuzzing port: answers from the script, counts the traffic, keeps the last torque.
template <typename T>
class ScriptedPort final : public gyro::GyroPort<T> {
 public:
  PortScript<T> script{};
  int reads{0};
  int writes{0};
  gyro::Vector2<T> torque{gyro::Vector2<T>::Zero()};

  [[nodiscard]] PortStatus read_pickoffs(gyro::PickoffReading<T>& out) noexcept override {
    ++reads;
    if (script.read_status == PortStatus::kOk) out = script.reading;
    return script.read_status;
  }
  [[nodiscard]] PortStatus write_torquer(const gyro::Vector2<T>& t) noexcept override {
    ++writes;
    torque = t;
    return script.write_status;
  }
};

// The seeker example (gyro/seeker_example.hpp) with fault persistences and settling short
// enough for a few hundred ticks to reach every mode.
template <typename T>
gyro::GyroComponentConfig<T> nominal_config() {
  gyro::GyroComponentConfig<T> c = gyro::SeekerExample<T>::component();
  c.residual_persistence_ticks = 8;
  c.invalid_persistence_ticks = 5;
  c.spin_low_persistence_ticks = 5;
  c.torquer_fail_persistence_ticks = 3;
  c.uncage_settle_ticks = 4;
  return c;
}

// Overrides the fields selected by a 32-bit mask (values of the order of the nominal ones,
// or anything at all): bit i is the i-th number or count of the configuration's field table
// (gyro/config_fields.hpp), in table order; the flags have header bits of their own.
template <typename T>
void override_fields(Bytes& in, gyro::GyroComponentConfig<T>& c) {
  const std::uint32_t mask = in.u32();
  unsigned bit = 0;
  gyro::visit_fields(
      [&](const gyro::Field&, auto& field) {
        using M = std::decay_t<decltype(field)>;
        if constexpr (std::is_same_v<M, T>) {
          if (bit < 32u && (mask & (1u << bit))) {
            const T scale = field == T(0) ? T(1) : field;
            field = in.value<T>(T(2) * scale);
          }
          ++bit;
        } else if constexpr (std::is_same_v<M, std::uint32_t>) {
          if (bit < 32u && (mask & (1u << bit))) {
            const std::uint8_t b = in.u8();
            field = (b & 0x80u) ? in.u32() : b;
          }
          ++bit;
        }
      },
      c);
}

template <typename T>
bool telemetry_finite(const gyro::GyroTelemetry<T>& t) {
  return finite_coeffs(t.gimbal_measured_rad) && finite_coeffs(t.gimbal_predicted_rad) &&
         finite_coeffs(t.residual_rad) && finite_coeffs(t.attitude_gyro_to_earth.coeffs()) &&
         finite_coeffs(t.precession_rate_rad_s) && finite_coeffs(t.rate_cmd_rad_s) && finite_coeffs(t.torque_cmd) &&
         finite_coeffs(t.nutation_amplitude_rad) && std::isfinite(t.spin_hz);
}

// Everything but flags and counters, bit for bit.
template <typename T>
bool same_except_flags_counters(const gyro::GyroTelemetry<T>& a, const gyro::GyroTelemetry<T>& b) {
  return a.tick == b.tick && a.mode == b.mode && same_bits(a.gimbal_measured_rad, b.gimbal_measured_rad) &&
         same_bits(a.gimbal_predicted_rad, b.gimbal_predicted_rad) && same_bits(a.residual_rad, b.residual_rad) &&
         same_bits(a.attitude_gyro_to_earth.coeffs(), b.attitude_gyro_to_earth.coeffs()) &&
         same_bits(a.precession_rate_rad_s, b.precession_rate_rad_s) &&
         same_bits(a.rate_cmd_rad_s, b.rate_cmd_rad_s) && same_bits(a.torque_cmd, b.torque_cmd) &&
         same_bits(a.nutation_amplitude_rad, b.nutation_amplitude_rad) && same_scalar_bits(a.spin_hz, b.spin_hz);
}
template <typename T>
bool same_telemetry(const gyro::GyroTelemetry<T>& a, const gyro::GyroTelemetry<T>& b) {
  return same_except_flags_counters(a, b) && a.flags == b.flags && a.counters == b.counters;
}

// Counters after a call that raised `flags`: each grows by one exactly when its bit is set.
bool counters_follow(const std::array<std::uint32_t, gyro::kComponentFlagCount>& before,
                     const std::array<std::uint32_t, gyro::kComponentFlagCount>& after, std::uint32_t flags) {
  for (std::size_t i = 0; i < before.size(); ++i) {
    const bool raised = (flags >> i) & 1u;
    const std::uint32_t expected =
        raised && before[i] != std::numeric_limits<std::uint32_t>::max() ? before[i] + 1u : before[i];
    if (after[i] != expected) return false;
  }
  return true;
}

bool known_request(ModeRequest r) {
  return r == ModeRequest::kNone || r == ModeRequest::kCage || r == ModeRequest::kUncage;
}

// The transitions of docs/component.md for one accepted tick. `settled`: the tick completes
// uncage_settle_ticks ticks in kUncaging.
bool legal_transition(GyroMode from, GyroMode to, ModeRequest r, std::uint32_t flags, bool settled) {
  if (from == to) return true;
  constexpr std::uint32_t kNotMeasurable =
      gyro::kPickoffInvalid | gyro::kPickoffStale | gyro::kPickoffJump | gyro::kNavInvalid;
  switch (from) {
    case GyroMode::kIdle: return false;  // only activate() leaves idle
    case GyroMode::kCaged:
      if (to == GyroMode::kFault) return true;
      return to == GyroMode::kUncaging && r == ModeRequest::kUncage && (flags & kNotMeasurable) == 0u;
    case GyroMode::kUncaging:
      if (to == GyroMode::kFault) return true;
      if (to == GyroMode::kCaged) return r == ModeRequest::kCage;
      return to == GyroMode::kFree && r != ModeRequest::kCage && settled;
    case GyroMode::kFree:
      if (to == GyroMode::kFault) return true;
      return to == GyroMode::kCaged && r == ModeRequest::kCage;
    case GyroMode::kFault: return to == GyroMode::kCaged && r == ModeRequest::kCage;
  }
  return false;
}

// The sticky inputs of the run, changed tick by tick by the operation words.
template <typename T>
struct Script {
  PortScript<T> port{};
  gyro::GuidanceInput<T> guidance{};
  std::uint64_t tick{0};
  int repeat{0};           // further ticks that repeat this tick's operation (sticky values,
                           // port failures, request; the sequence and the tick advance by one)
  bool poke_active{false}; // call configure()/activate() while active this tick

  Script() {
    port.reading.valid = true;
    port.reading.spin_valid = true;
    port.reading.spin_hz = T(400);
    guidance.nav_valid = true;
  }

  void next(Bytes& in) {
    ++port.reading.sequence;  // wraps, as the hardware counter does
    ++tick;
    if (repeat > 0) {  // the same port failures, request and calls as the last tick
      --repeat;
      return;
    }
    port.read_status = PortStatus::kOk;
    port.write_status = PortStatus::kOk;
    guidance.request = ModeRequest::kNone;
    poke_active = false;
    const std::uint16_t op = in.u16();
    gyro::PickoffReading<T>& rd = port.reading;
    if (op & (1u << 0)) {
      rd.gimbal_angle_rad(0) = in.value<T>(T(0.1));
      rd.gimbal_angle_rad(1) = in.value<T>(T(0.1));
    }
    if (op & (1u << 1)) {
      const std::uint8_t s = in.u8();
      switch (s & 3u) {
        case 0: --rd.sequence; break;  // stale: as last tick
        case 1: ++rd.sequence; break;  // one conversion missed
        case 2: rd.sequence = in.u32(); break;
        default: rd.sequence -= 2u; break;
      }
    }
    if (op & (1u << 2)) {
      const std::uint8_t b = in.u8();
      rd.valid = (b & 1u) != 0u;
      rd.spin_valid = (b & 2u) != 0u;
      if (b & 4u) rd.spin_hz = in.value<T>(T(400));
    }
    if (op & (1u << 3)) port.read_status = static_cast<PortStatus>(in.u8());
    if (op & (1u << 4)) port.write_status = static_cast<PortStatus>(in.u8());
    if (op & (1u << 5)) {
      const std::uint8_t b = in.u8();
      // 0..2 the known requests; otherwise an invalid enum value (>= 3).
      guidance.request = static_cast<ModeRequest>(b % 5u < 3u ? b % 5u : b);
    }
    if (op & (1u << 6)) {
      guidance.slew_rate_cmd_rad_s(0) = in.value<T>(T(2));
      guidance.slew_rate_cmd_rad_s(1) = in.value<T>(T(2));
    }
    if (op & (1u << 7)) navigation(in);
    if (op & (1u << 8)) {
      const std::uint8_t b = in.u8();
      if (b == 0u) {
        --tick;  // repeated
      } else if (b <= 200u) {
        tick += b - 1u;  // a gap
      } else if (b <= 250u) {
        tick -= 1u + (b - 200u);  // back in time (wraps below zero: a huge tick)
      } else {
        tick = in.u64();
      }
    }
    if (op & (1u << 9)) poke_active = true;
    if (op & (1u << 10)) repeat = in.u8();
  }

  void navigation(Bytes& in) {
    const std::uint8_t n = in.u8();
    if (n & 1u) guidance.nav_valid = !guidance.nav_valid;
    if (n & 2u) {  // a rotation, or what cos/sin make of NaN and huge angles
      const T roll = in.value<T>(T(3)), pitch = in.value<T>(T(3)), yaw = in.value<T>(T(3));
      guidance.R_earth_to_body = gyro::frame_rotation_y(pitch) * gyro::frame_rotation_z(yaw);
      const T c = std::cos(roll), s = std::sin(roll);
      gyro::Matrix3<T> rx;
      rx << T(1), T(0), T(0), T(0), c, s, T(0), -s, c;
      guidance.R_earth_to_body = rx * guidance.R_earth_to_body;
    }
    if (n & 4u) {  // disturb entries: near-rotations at the tolerance, reflections, garbage
      const std::uint8_t which = in.u8();
      guidance.R_earth_to_body(which % 3u, (which / 3u) % 3u) += in.value<T>(T(1e-4));
      if (which & 0x80u) guidance.R_earth_to_body.row(0) *= T(-1);
    }
    if (n & 8u) {
      guidance.body_rate_rad_s(0) = in.value<T>(T(1));
      guidance.body_rate_rad_s(1) = in.value<T>(T(1));
      guidance.body_rate_rad_s(2) = in.value<T>(T(1));
    }
  }
};

template <typename T>
void print_telemetry(const gyro::GyroTelemetry<T>& t) {
  const auto d = [](T v) { return static_cast<double>(v); };
  std::fprintf(stderr,
               "telemetry: tick %llu mode %s flags %#x\n  measured %g %g predicted %g %g residual %g %g\n"
               "  attitude (w x y z) %g %g %g %g precession %g %g\n  rate_cmd %g %g torque %g %g "
               "nutation %g %g spin %g\n",
               static_cast<unsigned long long>(t.tick), gyro::enum_name(t.mode), t.flags, d(t.gimbal_measured_rad(0)),
               d(t.gimbal_measured_rad(1)), d(t.gimbal_predicted_rad(0)), d(t.gimbal_predicted_rad(1)),
               d(t.residual_rad(0)), d(t.residual_rad(1)), d(t.attitude_gyro_to_earth.w()),
               d(t.attitude_gyro_to_earth.x()), d(t.attitude_gyro_to_earth.y()), d(t.attitude_gyro_to_earth.z()),
               d(t.precession_rate_rad_s(0)), d(t.precession_rate_rad_s(1)), d(t.rate_cmd_rad_s(0)),
               d(t.rate_cmd_rad_s(1)), d(t.torque_cmd(0)), d(t.torque_cmd(1)), d(t.nutation_amplitude_rad(0)),
               d(t.nutation_amplitude_rad(1)), d(t.spin_hz));
}

template <typename T>
void check_telemetry(const gyro::GyroComponent<T>& c) {
  const gyro::GyroTelemetry<T>& t = c.telemetry();
  if (!telemetry_finite(t)) print_telemetry(t);
  GYRO_FUZZ_CHECK(telemetry_finite(t));
  GYRO_FUZZ_CHECK(std::abs(t.attitude_gyro_to_earth.norm() - T(1)) <= T(1e-3));
  GYRO_FUZZ_CHECK(t.mode == c.mode());
  GYRO_FUZZ_CHECK((t.flags >> gyro::kComponentFlagCount) == 0u);
}

template <typename T>
void run(Bytes& in, std::uint8_t head) {
  ScriptedPort<T> port, twin_port;
  gyro::GyroComponent<T> c(port);
  gyro::GyroComponent<T> twin(twin_port);
  check_telemetry(c);

  gyro::GyroComponentConfig<T> cfg = nominal_config<T>();
  cfg.friction_compensation = (head & 8u) == 0u;
  cfg.use_spin_readback = (head & 16u) == 0u;
  Script<T> script;

  if (head & 4u) {  // steps before activation: refused and counted, nothing else changes
    const gyro::GyroTelemetry<T> before = c.telemetry();
    GYRO_FUZZ_CHECK(c.step(1, script.guidance) == Status::kNotConfigured);
    GYRO_FUZZ_CHECK(c.telemetry().flags == gyro::kNotActive);
    GYRO_FUZZ_CHECK(counters_follow(before.counters, c.telemetry().counters, gyro::kNotActive));
    GYRO_FUZZ_CHECK(same_except_flags_counters(before, c.telemetry()) && c.mode() == GyroMode::kIdle);
    GYRO_FUZZ_CHECK(c.activate() == Status::kNotConfigured && c.mode() == GyroMode::kIdle);
    GYRO_FUZZ_CHECK(port.reads == 0 && port.writes == 0);
    GYRO_FUZZ_CHECK(twin.step(1, script.guidance) == Status::kNotConfigured);  // counted alike
  }
  if (head & 2u) {
    gyro::GyroComponentConfig<T> odd = cfg;
    override_fields(in, odd);
    const gyro::ConfigCheck ck = c.configure(odd);
    if (ck.ok()) {
      cfg = odd;
    } else {
      GYRO_FUZZ_CHECK(ck.field != nullptr);
      GYRO_FUZZ_CHECK(c.mode() == GyroMode::kIdle && c.activate() == Status::kNotConfigured);
      GYRO_FUZZ_CHECK(c.step(1, script.guidance) == Status::kNotConfigured);
      GYRO_FUZZ_CHECK(twin.step(1, script.guidance) == Status::kNotConfigured);  // counted alike
    }
  }
  GYRO_FUZZ_CHECK(c.configure(cfg).ok());
  GYRO_FUZZ_CHECK(twin.configure(cfg).ok());
  GYRO_FUZZ_CHECK(c.mode() == GyroMode::kIdle);
  GYRO_FUZZ_CHECK(c.activate() == Status::kOk && c.mode() == GyroMode::kCaged);
  GYRO_FUZZ_CHECK(twin.activate() == Status::kOk);
  GYRO_FUZZ_CHECK(c.telemetry().mode == GyroMode::kCaged);
  check_telemetry(c);

  // The tick-count rule of docs/component.md, mirrored.
  bool have_tick = false, trusted = false;
  std::uint64_t last_tick = 0;
  std::uint32_t uncaging_ticks = 0;
  std::uint32_t quiet_ticks = 0;  // uncaging ticks in a row without stop protection
  gyro::Vector2<T> held = gyro::Vector2<T>::Zero();
  for (int k = 0; k < kMaxTicks && (!in.exhausted() || script.repeat > 0); ++k) {
    script.next(in);
    port.script = script.port;
    twin_port.script = script.port;
    const gyro::GuidanceInput<T>& g = script.guidance;

    const gyro::GyroTelemetry<T> before = c.telemetry();
    const GyroMode from = c.mode();
    const int reads = port.reads, writes = port.writes;
    const Status st = c.step(script.tick, g);
    const gyro::GyroTelemetry<T>& after = c.telemetry();
    check_telemetry(c);

    bool tick_bad = false;
    if (have_tick && script.tick != last_tick + 1u) {
      tick_bad = !(trusted && script.tick > last_tick && script.tick - last_tick <= cfg.max_tick_gap);
    }
    have_tick = true;
    trusted = !tick_bad;
    last_tick = script.tick;
    const bool nav_usable = g.nav_valid && gyro::all_finite(g.body_rate_rad_s) &&
                            g.body_rate_rad_s.cwiseAbs().maxCoeff() <= cfg.max_body_rate_rad_s &&
                            gyro::is_rotation(g.R_earth_to_body);
    const bool command_bad = !gyro::all_finite(g.slew_rate_cmd_rad_s) || !known_request(g.request) ||
                             (g.nav_valid && !nav_usable);
    GYRO_FUZZ_CHECK(st == ((command_bad || tick_bad) ? Status::kInputIgnored : Status::kOk));
    GYRO_FUZZ_CHECK(((after.flags & gyro::kTickInvalid) != 0u) == tick_bad);
    GYRO_FUZZ_CHECK(((after.flags & gyro::kCommandRejected) != 0u) == command_bad);
    GYRO_FUZZ_CHECK(((after.flags & gyro::kNavInvalid) != 0u) == !nav_usable);
    GYRO_FUZZ_CHECK(port.reads == reads + 1 && port.writes == writes + 1);
    GYRO_FUZZ_CHECK(after.tick == script.tick);
    GYRO_FUZZ_CHECK(counters_follow(before.counters, after.counters, after.flags));

    const GyroMode to = c.mode();
#if defined(GYRO_FUZZ_TRACE)
    std::fprintf(stderr, "tick %llu %s -> %s flags %#x torque %g %g\n", static_cast<unsigned long long>(script.tick),
                 gyro::enum_name(from), gyro::enum_name(to), after.flags, static_cast<double>(port.torque(0)),
                 static_cast<double>(port.torque(1)));
#endif
    const ModeRequest request = known_request(g.request) ? g.request : ModeRequest::kNone;
    if (from == GyroMode::kUncaging) ++uncaging_ticks;
    const bool settled = from == GyroMode::kUncaging && uncaging_ticks >= cfg.uncage_settle_ticks;
    GYRO_FUZZ_CHECK(legal_transition(from, to, request, after.flags, settled));
    if (from == GyroMode::kUncaging && settled && request != ModeRequest::kCage) {
      GYRO_FUZZ_CHECK(to == GyroMode::kFree || to == GyroMode::kFault);
    }
    if (to != GyroMode::kUncaging) uncaging_ticks = 0;
    GYRO_FUZZ_CHECK(((after.flags & gyro::kFaultLatched) != 0u) == (to == GyroMode::kFault));

    const gyro::Vector2<T>& w = port.torque;
    GYRO_FUZZ_CHECK(finite_coeffs(w));
    GYRO_FUZZ_CHECK(w.cwiseAbs().maxCoeff() <= cfg.max_torque * (T(1) + T(4) * std::numeric_limits<T>::epsilon()));
    // Torquers off: at once in safe mode; while uncaging, unless stop protection acts, once the
    // torque shaper's history (2 kShaperMaxSpacing ticks) holds only such ticks.
    quiet_ticks = (to == GyroMode::kUncaging && (after.flags & gyro::kGimbalStopProtect) == 0u) ? quiet_ticks + 1u : 0u;
    if (to == GyroMode::kFault || quiet_ticks > 2u * gyro::kShaperMaxSpacing) GYRO_FUZZ_CHECK(w.isZero(T(0)));
    if (script.port.write_status == PortStatus::kOk) held = w;
    GYRO_FUZZ_CHECK(same_bits(after.torque_cmd, held));

    // The twin, handed the same calls: the same telemetry, the same torque.
    GYRO_FUZZ_CHECK(twin.step(script.tick, g) == st);
    GYRO_FUZZ_CHECK(same_telemetry(after, twin.telemetry()));
    GYRO_FUZZ_CHECK(same_bits(port.torque, twin_port.torque));

    if (script.poke_active) {  // refused once active, nothing changes
      const gyro::GyroTelemetry<T> t0 = c.telemetry();
      const GyroMode m0 = c.mode();
      GYRO_FUZZ_CHECK(c.configure(nominal_config<T>()).status == Status::kWrongMode);
      GYRO_FUZZ_CHECK(c.activate() == Status::kWrongMode);
      GYRO_FUZZ_CHECK(c.mode() == m0 && same_telemetry(t0, c.telemetry()));
      GYRO_FUZZ_CHECK(same_scalar_bits(c.config().max_torque, cfg.max_torque) &&
                      c.config().uncage_settle_ticks == cfg.uncage_settle_ticks);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  const std::uint8_t head = in.u8();
  if (head & 1u) {
    run<float>(in, head);
  } else {
    run<double>(in, head);
  }
  return 0;
}
