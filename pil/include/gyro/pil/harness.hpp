// The processor-in-the-loop harness (docs/pil-protocol.md): what the host and the target
// exchange besides the gyro link itself, in gyro::link frames on the same serial line.
//
//   target                                   host
//   hello           ---------------------->                    scalar, timer clock
//                   <----------------------  config            component configuration, tick period
//   config_ack      ---------------------->                    configure()'s verdict
//   then once per cycle, in the target's frozen time (its timer paused):
//   tick_out + G bytes + telemetry --------->                  the cycle that ran (its step,
//                                                               torque bytes, telemetry) and the
//                                                               tick the target runs next
//                   <----------------------  tick_in + N bytes guidance input for that tick and
//                                                               the gyro-link bytes that arrived
//                                                               during it (pickoff frames, or
//                                                               whatever the wire faults left)
//                   <----------------------  stop              (instead of tick_in) end of run
//
// The gyro-link bytes ride inside the record of their tick, so the target sees exactly the
// same bytes in the same tick on every run, whatever the host's timing: a dropped frame, a
// stalled link and a late frame are reproducible.
//
// Payloads (little-endian; R = one real of the target's scalar, binary32 or binary64):
//   hello       u16 version | u8 real bytes | u32 timer clock Hz                       7
//   config      the component's reals | u8 switches | u32 counts | u32 timer period  19 R + 33
//               (each in its field table's order, gyro/config_fields.hpp)
//   config_ack  u8 status | 24 chars of the refused field's name (NUL-padded)          25
//   tick_in     u32 tick | u8 gyro bytes N | u8 request (bits 0-1), nav valid (bit 2)
//               | R slew[2] | R R_earth_to_body[9] (row-major) | R body rate[2]      6 + 13 R
//   tick_out    u32 next tick | u8 has previous | u32 previous tick | u8 step status
//               | u32 step timer counts | u8 gyro bytes G | u32 released | u32 cycles
//               | u32 skipped | u32 overruns | u8 overrun | 10 x u32 port counters
//               | 4 x u32 decoder counters                                           88
//   telemetry   u32 tick | u8 mode | u32 flags | 21 x u32 counters | 19 R             93 + 19 R
//               (a counter per flag bit, kComponentFlagCount)
//   stop        u8 reason                                                               1
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "gyro/component_types.hpp"
#include "gyro/config_check.hpp"
#include "gyro/link/byte_fifo.hpp"
#include "gyro/link/frame.hpp"
#include "gyro/link/frame_decoder.hpp"
#include "gyro/link/link_gyro_port.hpp"
#include "gyro/link/wire.hpp"
#include "gyro/rate_group.hpp"

namespace gyro::pil {

inline constexpr std::uint16_t kProtocolVersion = 2;

// The target's gyro line. Its rate is set by the tick records: the bytes of a tick ride in its
// tick_in, counted in one byte, so the line delivers at most 255 bytes a tick (gyro_sil --pil
// refuses a tick with more). The receive FIFO holds a whole tick's delivery, and the port
// drains up to the FIFO's size in a read: every read empties what the line brought, and a
// noisy tick cannot leave a backlog that grows until the FIFO drops bytes. The work a read
// does stays bounded: 256 bytes through the decoder. (A read of 4 frames, the port's default
// of 144 bytes in double, 96 in float, fell behind 120 bytes of noise a tick plus the frame:
// on the M7, 10 readings of 3,001 arrived and the component latched a fault.)
inline constexpr std::size_t kGyroLineBytesPerTick = 255;
inline constexpr std::size_t kGyroRxBytes = 256;
inline constexpr std::size_t kGyroTxBytes = 64;  // one torque frame a step (23 bytes in double)
static_assert(kGyroRxBytes >= kGyroLineBytesPerTick, "the receive FIFO holds a tick's bytes");
using GyroWire = link::FifoLink<kGyroRxBytes, kGyroTxBytes>;
template <typename T>
using GyroLinkPort = LinkGyroPort<T, kGyroRxBytes>;
static_assert(link::kGyroLinkFrameBytes<double> <= kGyroTxBytes, "room for a torque frame");

inline constexpr std::uint8_t kHello = 0x10u;
inline constexpr std::uint8_t kConfig = 0x11u;
inline constexpr std::uint8_t kConfigAck = 0x12u;
inline constexpr std::uint8_t kTickIn = 0x13u;
inline constexpr std::uint8_t kTickOut = 0x14u;
inline constexpr std::uint8_t kTelemetry = 0x15u;
inline constexpr std::uint8_t kStop = 0x16u;

// The configuration message carries GyroComponentConfig's numbers, then its switches as the
// bits of one byte, then its counts, each in the order of its field table.
inline constexpr std::size_t kConfigReals = count_fields<GyroComponentConfig<float>, std::is_floating_point>();
inline constexpr std::size_t kConfigCounts = count_fields<GyroComponentConfig<float>, CountFields>();
inline constexpr std::size_t kConfigSwitches = count_fields<GyroComponentConfig<float>, SwitchFields>();
static_assert(kConfigSwitches <= 8, "the switches travel as the bits of one byte");
inline constexpr std::size_t kTelemetryReals = 19;
inline constexpr std::size_t kFieldNameBytes = 24;

template <typename T>
struct HarnessMessages {
  static constexpr std::size_t kHelloPayload = 7;
  static constexpr std::size_t kConfigPayload = kConfigReals * sizeof(T) + 1 + 4 * kConfigCounts + 4;
  static constexpr std::size_t kConfigAckPayload = 1 + kFieldNameBytes;
  static constexpr std::size_t kTickInPayload = 6 + 14 * sizeof(T);
  static constexpr std::size_t kTickOutPayload = 88;
  static constexpr std::size_t kTelemetryPayload = 9 + 4 * kComponentFlagCount + kTelemetryReals * sizeof(T);
  static constexpr std::size_t kStopPayload = 1;
  static constexpr std::size_t kMaxPayload = kTelemetryPayload;

  [[nodiscard]] static constexpr int payload_length(std::uint8_t type) noexcept {
    using link::frame_type;
    if (type == frame_type<T>(kHello)) return static_cast<int>(kHelloPayload);
    if (type == frame_type<T>(kConfig)) return static_cast<int>(kConfigPayload);
    if (type == frame_type<T>(kConfigAck)) return static_cast<int>(kConfigAckPayload);
    if (type == frame_type<T>(kTickIn)) return static_cast<int>(kTickInPayload);
    if (type == frame_type<T>(kTickOut)) return static_cast<int>(kTickOutPayload);
    if (type == frame_type<T>(kTelemetry)) return static_cast<int>(kTelemetryPayload);
    if (type == frame_type<T>(kStop)) return static_cast<int>(kStopPayload);
    return -1;
  }
};
static_assert(HarnessMessages<double>::kMaxPayload <= link::kMaxPayloadBytes, "one-byte length field");
static_assert(HarnessMessages<double>::kConfigPayload <= HarnessMessages<double>::kMaxPayload, "largest");

template <typename T>
using HarnessFrame = link::Frame<HarnessMessages<T>::kMaxPayload>;
template <typename T>
using HarnessDecoder = link::FrameDecoder<HarnessMessages<T>>;
template <typename T>
inline constexpr std::size_t kHarnessFrameBytes = link::kFrameOverhead + HarnessMessages<T>::kMaxPayload;

// ---- the messages as values ----------------------------------------------------------------

struct Hello {
  std::uint16_t version{kProtocolVersion};
  std::uint8_t real_bytes{};
  std::uint32_t timer_hz{};  // the clock of the tick timer (SysTick: the core clock)
};

template <typename T>
struct Config {
  GyroComponentConfig<T> component{};
  std::uint32_t timer_period{};  // timer counts per tick (SysTick: reload + 1)
};

struct ConfigAck {
  Status status{Status::kOk};
  std::array<char, kFieldNameBytes> field{};  // NUL-padded; empty when accepted
};

template <typename T>
struct TickIn {
  std::uint32_t tick{};        // low 32 bits of the tick these inputs are for
  std::uint8_t gyro_bytes{};   // gyro-link bytes that follow the frame
  GuidanceInput<T> guidance{};
};

struct TickOut {
  std::uint32_t next_tick{};      // low 32 bits of the tick the target runs next
  bool has_previous{false};       // a cycle ran before this report (its results follow)
  std::uint32_t previous_tick{};
  Status step_status{Status::kOk};
  std::uint32_t step_counts{};    // timer counts the component's step took
  std::uint8_t gyro_bytes{};      // gyro-link bytes (torque frames) that follow the frame
  std::uint32_t released{};       // rate group: ticks released (low 32 bits)
  std::uint32_t cycles{};         // cycles run (low 32 bits)
  std::uint32_t skipped{};        // released ticks never run (low 32 bits)
  std::uint32_t overruns{};
  bool overrun{false};            // the previous cycle overran
  LinkPortCounters port{};
  std::uint32_t header_errors{};  // the port's decoder
  std::uint32_t crc_errors{};
  std::uint32_t bytes_skipped{};
  std::uint32_t decoder_frames{};
};

// ---- member tables: one list per struct, read by the encoder and the decoder alike ---------
// (GyroComponentConfig's is its field table, gyro/config_fields.hpp.)

template <typename T>
struct TelemetryFields {
  using M = GyroTelemetry<T>;
  static constexpr Vector2<T> M::*kPairs[7] = {
      &M::gimbal_measured_rad, &M::gimbal_predicted_rad, &M::residual_rad,     &M::precession_rate_rad_s,
      &M::rate_cmd_rad_s,      &M::torque_cmd,           &M::nutation_amplitude_rad,
  };
};

inline constexpr std::uint32_t LinkPortCounters::*kPortCounters[10] = {
    &LinkPortCounters::readings,   &LinkPortCounters::duplicates, &LinkPortCounters::frames_lost,
    &LinkPortCounters::superseded, &LinkPortCounters::malformed,  &LinkPortCounters::unexpected,
    &LinkPortCounters::timeouts,   &LinkPortCounters::bus_errors, &LinkPortCounters::torque_frames,
    &LinkPortCounters::torque_refused,
};

// ---- encoding -------------------------------------------------------------------------------

namespace detail {

template <typename T>
[[nodiscard]] HarnessFrame<T> start(std::uint8_t id, std::uint8_t seq) noexcept {
  HarnessFrame<T> f;
  f.type = link::frame_type<T>(id);
  f.seq = seq;
  f.length = static_cast<std::uint8_t>(HarnessMessages<T>::payload_length(f.type));
  return f;
}

// An encoder's last step: a payload that does not fill the message's length exactly (a
// layout error) makes the frame one no receiver accepts (length 0).
template <typename T, std::size_t N>
[[nodiscard]] HarnessFrame<T> seal(HarnessFrame<T> f, const link::WireWriter<N>& w) noexcept {
  if (!w.ok() || w.position() != f.length) f.length = 0;
  return f;
}

// The last value of each enumeration the harness carries, from its table of names.
inline constexpr Status kLastStatus = static_cast<Status>(enum_names(Status{}).size() - 1u);
inline constexpr GyroMode kLastMode = static_cast<GyroMode>(enum_names(GyroMode{}).size() - 1u);

// The number of members of an aggregate (the largest brace initialiser it accepts).
struct AnyField {
  template <typename U>
  constexpr operator U() const noexcept;  // NOLINT(google-explicit-constructor): only in decltype
};
template <typename A, typename Seq, typename = void>
struct BraceInitialisable : std::false_type {};
template <typename A, std::size_t... I>
struct BraceInitialisable<A, std::index_sequence<I...>, std::void_t<decltype(A{(void(I), AnyField{})...})>>
    : std::true_type {};
template <typename A, std::size_t N = 0>
[[nodiscard]] constexpr std::size_t field_count() noexcept {
  if constexpr (BraceInitialisable<A, std::make_index_sequence<N + 1>>::value) {
    return field_count<A, N + 1>();
  } else {
    return N;
  }
}

// Enumerations and booleans arrive as bytes: only the values they can take are accepted, so
// every frame a decoder accepts encodes back to the same bytes.
[[nodiscard]] constexpr bool known_status(std::uint8_t v) noexcept {
  return v <= static_cast<std::uint8_t>(kLastStatus);
}
[[nodiscard]] constexpr bool known_mode(std::uint8_t v) noexcept {
  return v <= static_cast<std::uint8_t>(kLastMode);
}
[[nodiscard]] constexpr bool boolean(std::uint8_t v) noexcept { return v <= 1u; }

// A decoder's last check: every byte of the payload read, none past it.
template <std::size_t N>
[[nodiscard]] bool consumed(const link::WireReader<N>& r, std::uint8_t length) noexcept {
  return r.ok() && r.position() == length;
}

// The frame is of message `id` in T's format with its exact length.
template <typename T>
[[nodiscard]] bool is(const HarnessFrame<T>& f, std::uint8_t id) noexcept {
  return f.type == link::frame_type<T>(id) &&
         static_cast<int>(f.length) == HarnessMessages<T>::payload_length(f.type);
}

}  // namespace detail

// Every member of the configuration has a row in its field table, and the message carries
// every row (a member of another kind breaks the build here).
static_assert(detail::field_count<GyroComponentConfig<float>>() == count_fields<GyroComponentConfig<float>, AnyField>(),
              "a GyroComponentConfig member without a row in its field table");
static_assert(kConfigReals + kConfigCounts + kConfigSwitches == count_fields<GyroComponentConfig<float>, AnyField>(),
              "the configuration message carries numbers, counts and switches only");

template <typename T>
[[nodiscard]] HarnessFrame<T> encode_hello(const Hello& h, std::uint8_t seq) noexcept {
  HarnessFrame<T> f = detail::start<T>(kHello, seq);
  link::WireWriter w(f.payload, 0);
  w.u16(h.version);
  w.u8(h.real_bytes);
  w.u32(h.timer_hz);
  return detail::seal<T>(f, w);
}
template <typename T>
[[nodiscard]] bool decode_hello(const HarnessFrame<T>& f, Hello& out) noexcept {
  if (!detail::is<T>(f, kHello)) return false;
  link::WireReader r(f.payload, 0);
  Hello h;
  h.version = r.u16();
  h.real_bytes = r.u8();
  h.timer_hz = r.u32();
  if (!detail::consumed(r, f.length)) return false;
  out = h;
  return true;
}

template <typename T>
[[nodiscard]] HarnessFrame<T> encode_config(const Config<T>& c, std::uint8_t seq) noexcept {
  HarnessFrame<T> f = detail::start<T>(kConfig, seq);
  link::WireWriter w(f.payload, 0);
  visit_fields([&w](const Field&, const auto& m) noexcept {
    if constexpr (std::is_same_v<std::decay_t<decltype(m)>, T>) w.real(m);
  }, c.component);
  std::uint8_t switches = 0;
  unsigned bit = 0;
  visit_fields([&](const Field&, const auto& m) noexcept {
    if constexpr (std::is_same_v<std::decay_t<decltype(m)>, bool>) {
      if (m) switches = static_cast<std::uint8_t>(switches | (1u << bit));
      ++bit;
    }
  }, c.component);
  w.u8(switches);
  visit_fields([&w](const Field&, const auto& m) noexcept {
    if constexpr (std::is_same_v<std::decay_t<decltype(m)>, std::uint32_t>) w.u32(m);
  }, c.component);
  w.u32(c.timer_period);
  return detail::seal<T>(f, w);
}
template <typename T>
[[nodiscard]] bool decode_config(const HarnessFrame<T>& f, Config<T>& out) noexcept {
  if (!detail::is<T>(f, kConfig)) return false;
  link::WireReader r(f.payload, 0);
  Config<T> c;
  visit_fields([&r](const Field&, auto& m) noexcept {
    if constexpr (std::is_same_v<std::decay_t<decltype(m)>, T>) m = r.template real<T>();
  }, c.component);
  const std::uint8_t switches = r.u8();
  if ((switches >> kConfigSwitches) != 0u) return false;
  unsigned bit = 0;
  visit_fields([&](const Field&, auto& m) noexcept {
    if constexpr (std::is_same_v<std::decay_t<decltype(m)>, bool>) m = ((switches >> bit++) & 1u) != 0u;
  }, c.component);
  visit_fields([&r](const Field&, auto& m) noexcept {
    if constexpr (std::is_same_v<std::decay_t<decltype(m)>, std::uint32_t>) m = r.u32();
  }, c.component);
  c.timer_period = r.u32();
  if (!detail::consumed(r, f.length)) return false;
  out = c;
  return true;
}

template <typename T>
[[nodiscard]] HarnessFrame<T> encode_config_ack(const ConfigAck& a, std::uint8_t seq) noexcept {
  HarnessFrame<T> f = detail::start<T>(kConfigAck, seq);
  link::WireWriter w(f.payload, 0);
  w.u8(static_cast<std::uint8_t>(a.status));
  for (char ch : a.field) w.u8(static_cast<std::uint8_t>(ch));
  return detail::seal<T>(f, w);
}
template <typename T>
[[nodiscard]] bool decode_config_ack(const HarnessFrame<T>& f, ConfigAck& out) noexcept {
  if (!detail::is<T>(f, kConfigAck)) return false;
  link::WireReader r(f.payload, 0);
  ConfigAck a;
  const std::uint8_t status = r.u8();
  std::generate(a.field.begin(), a.field.end(), [&r] { return static_cast<char>(r.u8()); });
  if (!detail::consumed(r, f.length) || !detail::known_status(status) || a.field.back() != '\0') return false;
  a.status = static_cast<Status>(status);
  out = a;
  return true;
}

// The refused field's name, truncated to fit (NUL-terminated).
[[nodiscard]] inline ConfigAck make_config_ack(const ConfigCheck& check) noexcept {
  ConfigAck a;
  a.status = check.status;
  const char* name = check.field;
  for (std::size_t i = 0; name != nullptr && i + 1 < a.field.size(); ++i) {
    const char ch = name[i];  // NOLINT(cppcoreguidelines-pro-bounds-pointer-arithmetic): C string, stops at NUL
    if (ch == '\0') break;
    a.field[i] = ch;
  }
  return a;
}

template <typename T>
[[nodiscard]] HarnessFrame<T> encode_tick_in(const TickIn<T>& t, std::uint8_t seq) noexcept {
  HarnessFrame<T> f = detail::start<T>(kTickIn, seq);
  link::WireWriter w(f.payload, 0);
  w.u32(t.tick);
  w.u8(t.gyro_bytes);
  const GuidanceInput<T>& g = t.guidance;
  w.u8(static_cast<std::uint8_t>((static_cast<unsigned>(g.request) & 0x3u) | (g.nav_valid ? 0x4u : 0u)));
  w.real(g.slew_rate_cmd_rad_s(0));
  w.real(g.slew_rate_cmd_rad_s(1));
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) w.real(g.R_earth_to_body(row, col));
  }
  w.real(g.body_rate_rad_s(0));
  w.real(g.body_rate_rad_s(1));
  w.real(g.body_rate_rad_s(2));
  return detail::seal<T>(f, w);
}
// false: not a tick_in frame, or reserved bits set. Values are passed on as received: the
// component checks them (a non-finite command is its to refuse).
template <typename T>
[[nodiscard]] bool decode_tick_in(const HarnessFrame<T>& f, TickIn<T>& out) noexcept {
  if (!detail::is<T>(f, kTickIn)) return false;
  link::WireReader r(f.payload, 0);
  TickIn<T> t;
  t.tick = r.u32();
  t.gyro_bytes = r.u8();
  const std::uint8_t bits = r.u8();
  if ((bits & ~0x7u) != 0u) return false;
  t.guidance.request = static_cast<ModeRequest>(bits & 0x3u);
  t.guidance.nav_valid = (bits & 0x4u) != 0u;
  t.guidance.slew_rate_cmd_rad_s(0) = r.template real<T>();
  t.guidance.slew_rate_cmd_rad_s(1) = r.template real<T>();
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) t.guidance.R_earth_to_body(row, col) = r.template real<T>();
  }
  t.guidance.body_rate_rad_s(0) = r.template real<T>();
  t.guidance.body_rate_rad_s(1) = r.template real<T>();
  t.guidance.body_rate_rad_s(2) = r.template real<T>();
  if (!detail::consumed(r, f.length)) return false;
  out = t;
  return true;
}

template <typename T>
[[nodiscard]] HarnessFrame<T> encode_tick_out(const TickOut& t, std::uint8_t seq) noexcept {
  HarnessFrame<T> f = detail::start<T>(kTickOut, seq);
  link::WireWriter w(f.payload, 0);
  w.u32(t.next_tick);
  w.u8(t.has_previous ? 1u : 0u);
  w.u32(t.previous_tick);
  w.u8(static_cast<std::uint8_t>(t.step_status));
  w.u32(t.step_counts);
  w.u8(t.gyro_bytes);
  w.u32(t.released);
  w.u32(t.cycles);
  w.u32(t.skipped);
  w.u32(t.overruns);
  w.u8(t.overrun ? 1u : 0u);
  for (std::uint32_t LinkPortCounters::*m : kPortCounters) w.u32(t.port.*m);
  w.u32(t.header_errors);
  w.u32(t.crc_errors);
  w.u32(t.bytes_skipped);
  w.u32(t.decoder_frames);
  return detail::seal<T>(f, w);
}
template <typename T>
[[nodiscard]] bool decode_tick_out(const HarnessFrame<T>& f, TickOut& out) noexcept {
  if (!detail::is<T>(f, kTickOut)) return false;
  link::WireReader r(f.payload, 0);
  TickOut t;
  t.next_tick = r.u32();
  const std::uint8_t has_previous = r.u8();
  t.has_previous = has_previous != 0u;
  t.previous_tick = r.u32();
  const std::uint8_t step_status = r.u8();
  t.step_status = static_cast<Status>(step_status);
  t.step_counts = r.u32();
  t.gyro_bytes = r.u8();
  t.released = r.u32();
  t.cycles = r.u32();
  t.skipped = r.u32();
  t.overruns = r.u32();
  const std::uint8_t overrun = r.u8();
  t.overrun = overrun != 0u;
  for (std::uint32_t LinkPortCounters::*m : kPortCounters) t.port.*m = r.u32();
  t.header_errors = r.u32();
  t.crc_errors = r.u32();
  t.bytes_skipped = r.u32();
  t.decoder_frames = r.u32();
  if (!detail::consumed(r, f.length) || !detail::boolean(has_previous) || !detail::known_status(step_status) ||
      !detail::boolean(overrun)) {
    return false;
  }
  out = t;
  return true;
}

template <typename T>
[[nodiscard]] HarnessFrame<T> encode_telemetry(const GyroTelemetry<T>& m, std::uint8_t seq) noexcept {
  HarnessFrame<T> f = detail::start<T>(kTelemetry, seq);
  link::WireWriter w(f.payload, 0);
  w.u32(static_cast<std::uint32_t>(m.tick & 0xFFFFFFFFu));
  w.u8(static_cast<std::uint8_t>(m.mode));
  w.u32(m.flags);
  for (std::uint32_t c : m.counters) w.u32(c);
  for (Vector2<T> GyroTelemetry<T>::*p : TelemetryFields<T>::kPairs) {
    w.real((m.*p)(0));
    w.real((m.*p)(1));
  }
  w.real(m.attitude_gyro_to_earth.w());
  w.real(m.attitude_gyro_to_earth.x());
  w.real(m.attitude_gyro_to_earth.y());
  w.real(m.attitude_gyro_to_earth.z());
  w.real(m.spin_hz);
  return detail::seal<T>(f, w);
}
// The tick comes back as its low 32 bits (the receiver knows the rest).
template <typename T>
[[nodiscard]] bool decode_telemetry(const HarnessFrame<T>& f, GyroTelemetry<T>& out) noexcept {
  if (!detail::is<T>(f, kTelemetry)) return false;
  link::WireReader r(f.payload, 0);
  GyroTelemetry<T> m;
  m.tick = r.u32();
  const std::uint8_t mode = r.u8();
  m.mode = static_cast<GyroMode>(mode);
  m.flags = r.u32();
  std::generate(m.counters.begin(), m.counters.end(), [&r] { return r.u32(); });
  for (Vector2<T> GyroTelemetry<T>::*p : TelemetryFields<T>::kPairs) {
    (m.*p)(0) = r.template real<T>();
    (m.*p)(1) = r.template real<T>();
  }
  const T qw = r.template real<T>(), qx = r.template real<T>(), qy = r.template real<T>(), qz = r.template real<T>();
  m.attitude_gyro_to_earth = Quaternion<T>(qw, qx, qy, qz);
  m.spin_hz = r.template real<T>();
  if (!detail::consumed(r, f.length) || !detail::known_mode(mode)) return false;
  out = m;
  return true;
}

template <typename T>
[[nodiscard]] HarnessFrame<T> encode_stop(std::uint8_t reason, std::uint8_t seq) noexcept {
  HarnessFrame<T> f = detail::start<T>(kStop, seq);
  f.payload[0] = reason;
  return f;
}

}  // namespace gyro::pil
