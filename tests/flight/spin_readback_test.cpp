// The spin flown (gyro/spin_readback.hpp): the readback when usable, else the nominal spin; the
// low-spin flag at and below the minimum.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "gyro/seeker_component_example.hpp"
#include "gyro/spin_readback.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace spin_readback_test {

const GyroComponentConfig<double> kSeeker = SeekerComponentExample<double>::component();

PickoffReading<double> readback(double hz) {
  PickoffReading<double> r;
  r.valid = true;
  r.spin_valid = true;
  r.spin_hz = hz;
  return r;
}

TEST(SpinReadback, AUsableReadbackIsFlown) {
  GYRO_VERIFIES("SPIN-1");
  const SpinFlown<double> s = spin_flown(readback(390.0), true, kSeeker);
  EXPECT_EQ(s.hz, 390.0);
  EXPECT_EQ(s.flags, 0u);
}

TEST(SpinReadback, AnUnusableReadbackGivesTheNominalSpin) {
  GYRO_VERIFIES("SPIN-1");
  PickoffReading<double> unmarked = readback(350.0);
  unmarked.spin_valid = false;
  GyroComponentConfig<double> no_readback = kSeeker;
  no_readback.use_spin_readback = false;
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(spin_flown(readback(350.0), false, kSeeker).hz, kSeeker.nominal_spin_hz) << "the read failed";
  EXPECT_EQ(spin_flown(unmarked, true, kSeeker).hz, kSeeker.nominal_spin_hz);
  EXPECT_EQ(spin_flown(readback(350.0), true, no_readback).hz, kSeeker.nominal_spin_hz);
  for (const double hz : {std::numeric_limits<double>::quiet_NaN(), inf, -inf, -1.0, -1e-300}) {
    EXPECT_EQ(spin_flown(readback(hz), true, kSeeker).hz, kSeeker.nominal_spin_hz) << hz;
  }
}

// A readback the port marks invalid is no spin, however plausible its value: the nominal is
// flown and nothing is low; marked valid again, it is flown.
TEST(SpinReadback, OneMarkedInvalidIsNeitherFlownNorLow) {
  GYRO_VERIFIES("SPIN-1", "SPIN-2");
  for (const double hz : {350.0, 100.0}) {
    PickoffReading<double> unmarked = readback(hz);
    unmarked.spin_valid = false;
    const SpinFlown<double> s = spin_flown(unmarked, true, kSeeker);
    EXPECT_EQ(s.hz, kSeeker.nominal_spin_hz) << hz;
    EXPECT_EQ(s.flags, 0u) << hz;
  }
  const SpinFlown<double> marked = spin_flown(readback(100.0), true, kSeeker);
  EXPECT_EQ(marked.hz, 100.0) << "marked valid again: used";
  EXPECT_EQ(marked.flags, static_cast<std::uint32_t>(kSpinLow));
}

TEST(SpinReadback, AnUnrepresentableMomentumGivesTheNominalSpin) {
  GYRO_VERIFIES("SPIN-1");
  // H = 2 pi J0 spin: with J0 = 1e6 a finite spin of 1e303 Hz has no finite momentum in double.
  GyroComponentConfig<double> heavy = kSeeker;
  heavy.spin_inertia = 1e6;
  EXPECT_EQ(spin_flown(readback(1e303), true, heavy).hz, heavy.nominal_spin_hz);
  EXPECT_EQ(spin_flown(readback(1e300), true, heavy).hz, 1e300) << "6.3e306: representable";
  GyroComponentConfig<float> f = SeekerComponentExample<float>::component();
  f.spin_inertia = 10.0F;
  PickoffReading<float> r;
  r.spin_valid = true;
  r.spin_hz = 1e38F;  // H = 6.3e39: beyond float
  EXPECT_EQ(spin_flown(r, true, f).hz, f.nominal_spin_hz);
}

TEST(SpinReadback, AZeroReadbackIsFlownAndLow) {
  GYRO_VERIFIES("SPIN-1", "SPIN-2");
  const SpinFlown<double> s = spin_flown(readback(0.0), true, kSeeker);
  EXPECT_EQ(s.hz, 0.0);
  EXPECT_EQ(s.flags, static_cast<std::uint32_t>(kSpinLow));
}

TEST(SpinReadback, LowIsStrictlyBelowTheMinimum) {
  GYRO_VERIFIES("SPIN-2");
  const SpinFlown<double> at = spin_flown(readback(kSeeker.min_spin_hz), true, kSeeker);
  EXPECT_EQ(at.hz, kSeeker.min_spin_hz);
  EXPECT_EQ(at.flags, 0u);
  EXPECT_EQ(spin_flown(readback(std::nextafter(kSeeker.min_spin_hz, 0.0)), true, kSeeker).flags,
            static_cast<std::uint32_t>(kSpinLow));
  GyroComponentConfig<double> low_nominal = kSeeker;
  low_nominal.use_spin_readback = false;
  low_nominal.nominal_spin_hz = 200.0;
  EXPECT_EQ(spin_flown(readback(400.0), true, low_nominal).flags, static_cast<std::uint32_t>(kSpinLow))
      << "the nominal spin is judged too";
}

}  // namespace spin_readback_test
}  // namespace gyro
