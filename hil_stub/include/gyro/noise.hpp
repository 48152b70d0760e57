// Counter-based noise for the software-in-the-loop stub: every sample is a pure function of
// (seed, stream id, sample index), so streams are independent of one another and of the
// order in which they are drawn. Changing one stream's id or seed leaves every other stream
// bit-identical, and a run can be replayed from any tick.
//
// Construction (no state but the key):
//   key    = mix(mix(mix(seed + G) + stream_id * M1) + M2)   the (seed, stream) pair, absorbed
//            one word at a time through a bijective 64-bit mixer; the mixer's non-linearity
//            keeps (seed, id) and (id, seed) apart, and the added constant keeps seed 0 off the
//            mixer's fixed point mix(0) = 0.
//   word_i = mix(key + (i + 1) * G)                         splitmix64 from the stream's key
//   gaussian_i = Box-Muller on (word_2i, word_2i+1), cosine branch.
// mix() is the splitmix64 finaliser (Stafford's variant 13), a bijection on 64-bit words.
// Two streams overlap only if their keys differ by a small multiple of G: probability
// ~n^2/2^64 for n samples.
#pragma once

#include <cmath>
#include <cstdint>

#include "gyro/rotor_parameters.hpp"

namespace gyro {

namespace noise_detail {

inline constexpr std::uint64_t kGolden = 0x9e3779b97f4a7c15ULL;  // 2^64 / phi, odd
inline constexpr std::uint64_t kStreamMul = 0xd1342543de82ef95ULL;  // odd multiplier
inline constexpr std::uint64_t kKeyTag = 0x632be59bd9b4e019ULL;

[[nodiscard]] constexpr std::uint64_t mix64(std::uint64_t x) noexcept {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebULL;
  x ^= x >> 31;
  return x;
}

// Uniform in (0, 1] from the top bits of a word (never 0: log() stays finite).
template <typename T>
[[nodiscard]] T uniform_open_closed(std::uint64_t w) noexcept {
  if constexpr (sizeof(T) == sizeof(double)) {
    return static_cast<T>((w >> 11) + 1u) * T(1.0 / 9007199254740992.0);  // 2^-53
  } else {
    return static_cast<T>((w >> 40) + 1u) * T(1.0f / 16777216.0f);  // 2^-24
  }
}

// Uniform in [0, 1).
template <typename T>
[[nodiscard]] T uniform_closed_open(std::uint64_t w) noexcept {
  if constexpr (sizeof(T) == sizeof(double)) {
    return static_cast<T>(w >> 11) * T(1.0 / 9007199254740992.0);
  } else {
    return static_cast<T>(w >> 40) * T(1.0f / 16777216.0f);
  }
}

}  // namespace noise_detail

// The key of one stream: a hash of (seed, stream id).
[[nodiscard]] constexpr std::uint64_t noise_stream_key(std::uint64_t seed, std::uint64_t stream_id) noexcept {
  using namespace noise_detail;
  std::uint64_t h = mix64(seed + kGolden);
  h = mix64(h + stream_id * kStreamMul);
  return mix64(h + kKeyTag);
}

// The i-th 64-bit word of the stream with key `key`.
[[nodiscard]] constexpr std::uint64_t noise_word(std::uint64_t key, std::uint64_t index) noexcept {
  return noise_detail::mix64(key + (index + 1u) * noise_detail::kGolden);
}

// One noise stream: white, zero-mean, unit-variance Gaussian samples indexed by a counter.
template <typename T>
class NoiseStream {
 public:
  constexpr NoiseStream() noexcept = default;
  constexpr NoiseStream(std::uint64_t seed, std::uint64_t stream_id) noexcept
      : key_(noise_stream_key(seed, stream_id)) {}

  [[nodiscard]] constexpr std::uint64_t key() const noexcept { return key_; }
  [[nodiscard]] constexpr std::uint64_t word(std::uint64_t index) const noexcept {
    return noise_word(key_, index);
  }
  // Uniform in [0, 1).
  [[nodiscard]] T uniform(std::uint64_t index) const noexcept {
    return noise_detail::uniform_closed_open<T>(word(index));
  }
  // Standard normal sample number `index` (Box-Muller; words 2i and 2i+1 of the stream).
  [[nodiscard]] T gaussian(std::uint64_t index) const noexcept {
    const T u1 = noise_detail::uniform_open_closed<T>(word(2u * index));
    const T u2 = noise_detail::uniform_closed_open<T>(word(2u * index + 1u));
    return std::sqrt(T(-2) * std::log(u1)) * std::cos(T(2) * kPi<T> * u2);
  }

 private:
  std::uint64_t key_{noise_stream_key(0u, 0u)};
};

}  // namespace gyro
