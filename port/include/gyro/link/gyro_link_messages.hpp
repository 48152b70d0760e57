// The messages between the gyro electronics and the flight computer (docs/pil-protocol.md):
//
//   pickoff (id 0x01, electronics -> flight computer), one conversion of the pickoffs:
//     u32 conversion sequence | u8 status (bit 0 data valid, bit 1 spin valid, bits 2-7 zero)
//     | real pitch_rad | real yaw_rad | real spin_hz                     5 + 3 reals
//   torque (id 0x02, flight computer -> electronics), the torquer command to hold:
//     real T1 (about the pitch gimbal axis) | real T2 (about the yaw gimbal axis)    2 reals
//
// Reals are the scalar the flight computer runs in (binary32 for float, binary64 for double),
// named in each frame's type byte; a receiver accepts only its own. Decoding checks what the
// frame cannot: reserved bits are zero. Values are passed on as received (a NaN angle is the
// caller's to reject, as from any converter).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>

#include "gyro/gyro_port.hpp"
#include "gyro/link/frame.hpp"
#include "gyro/link/wire.hpp"

namespace gyro::link {

inline constexpr std::uint8_t kPickoffMessage = 0x01u;
inline constexpr std::uint8_t kTorqueMessage = 0x02u;

inline constexpr std::uint8_t kPickoffValidBit = 0x01u;
inline constexpr std::uint8_t kSpinValidBit = 0x02u;

template <typename T>
inline constexpr std::size_t kPickoffPayload = 5 + 3 * sizeof(T);
template <typename T>
inline constexpr std::size_t kTorquePayload = 2 * sizeof(T);

// The message set of the gyro link, for FrameDecoder.
template <typename T>
struct GyroLinkMessages {
  static constexpr std::size_t kMaxPayload = kPickoffPayload<T>;
  [[nodiscard]] static constexpr int payload_length(std::uint8_t type) noexcept {
    if (type == frame_type<T>(kPickoffMessage)) return static_cast<int>(kPickoffPayload<T>);
    if (type == frame_type<T>(kTorqueMessage)) return static_cast<int>(kTorquePayload<T>);
    return -1;
  }
};

template <typename T>
using GyroLinkFrame = Frame<GyroLinkMessages<T>::kMaxPayload>;

// Largest encoded frame of the gyro link, in bytes.
template <typename T>
inline constexpr std::size_t kGyroLinkFrameBytes = kFrameOverhead + GyroLinkMessages<T>::kMaxPayload;

// An encoder's last step: a payload that does not fill the message's length exactly (a
// layout error) makes the frame one no receiver accepts (length 0).
template <std::size_t N, std::size_t M>
[[nodiscard]] Frame<N> sealed(Frame<N> f, const WireWriter<M>& w) noexcept {
  if (!w.ok() || w.position() != f.length) f.length = 0;
  return f;
}

template <typename T>
[[nodiscard]] GyroLinkFrame<T> encode_pickoff(const PickoffReading<T>& r, std::uint8_t seq) noexcept {
  GyroLinkFrame<T> f;
  f.type = frame_type<T>(kPickoffMessage);
  f.seq = seq;
  f.length = static_cast<std::uint8_t>(kPickoffPayload<T>);
  WireWriter w(f.payload, 0);
  w.u32(r.sequence);
  w.u8(static_cast<std::uint8_t>((r.valid ? kPickoffValidBit : 0u) | (r.spin_valid ? kSpinValidBit : 0u)));
  w.real(r.gimbal_angle_rad(0));
  w.real(r.gimbal_angle_rad(1));
  w.real(r.spin_hz);
  return sealed(f, w);
}

// false: not a pickoff frame of this scalar, or reserved bits set; `out` is then unchanged.
template <typename T>
[[nodiscard]] bool decode_pickoff(const GyroLinkFrame<T>& f, PickoffReading<T>& out) noexcept {
  if (f.type != frame_type<T>(kPickoffMessage) || f.length != kPickoffPayload<T>) return false;
  WireReader r(f.payload, 0);
  PickoffReading<T> p;
  p.sequence = r.u32();
  const std::uint8_t status = r.u8();
  if ((status & static_cast<std::uint8_t>(~(kPickoffValidBit | kSpinValidBit))) != 0u) return false;
  p.valid = (status & kPickoffValidBit) != 0u;
  p.spin_valid = (status & kSpinValidBit) != 0u;
  p.gimbal_angle_rad(0) = r.template real<T>();
  p.gimbal_angle_rad(1) = r.template real<T>();
  p.spin_hz = r.template real<T>();
  if (!r.ok() || r.position() != f.length) return false;
  out = p;
  return true;
}

template <typename T>
[[nodiscard]] GyroLinkFrame<T> encode_torque(const Eigen::Matrix<T, 2, 1>& torque, std::uint8_t seq) noexcept {
  GyroLinkFrame<T> f;
  f.type = frame_type<T>(kTorqueMessage);
  f.seq = seq;
  f.length = static_cast<std::uint8_t>(kTorquePayload<T>);
  WireWriter w(f.payload, 0);
  w.real(torque(0));
  w.real(torque(1));
  return sealed(f, w);
}

// false: not a torque frame of this scalar, or a non-finite command; `out` is then unchanged.
template <typename T>
[[nodiscard]] bool decode_torque(const GyroLinkFrame<T>& f, Eigen::Matrix<T, 2, 1>& out) noexcept {
  if (f.type != frame_type<T>(kTorqueMessage) || f.length != kTorquePayload<T>) return false;
  WireReader r(f.payload, 0);
  const T t1 = r.template real<T>();
  const T t2 = r.template real<T>();
  if (!r.ok() || r.position() != f.length || !std::isfinite(t1) || !std::isfinite(t2)) return false;
  out = Eigen::Matrix<T, 2, 1>(t1, t2);
  return true;
}

}  // namespace gyro::link
