// The example gyros (examples/include/gyro/) against the shipped scenarios: report_sample.json's
// gyro is ReportSample's; seeker_slew.json differs from SeekerExample in the fields listed; and
// the scenario form written from a configuration (gyro_section, component_section:
// gyro.examples in Python) reads back as it.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <sstream>
#include <string>
#include <type_traits>

#include "gyro/report_sample.hpp"
#include "gyro/seeker_example.hpp"
#include "scenario.hpp"
#include "sil_runner.hpp"

namespace gyro::sil {
namespace {

const std::filesystem::path kExampleScenarios = std::filesystem::path(GYRO_SOURCE_DIR) / "scenarios";

// Every field of `a` and `b` that differs, "name: a vs b", nested structs walked (a nested
// table's names already carry their struct's: "pickoff.lsb_rad").
template <class Config>
void differences(const Config& a, const Config& b, const std::string& prefix, std::string& out) {
  visit_fields(
      [&](const Field& f, const auto& x, const auto& y) {
        using M = std::decay_t<decltype(x)>;
        const std::string name = prefix + f.name;
        if constexpr (kHasFieldTable<M>) {
          bool qualified = false;
          visit_fields([&](const Field& g, const auto&) { qualified = qualified || std::string(g.name).find('.') != std::string::npos; }, x);
          differences(x, y, qualified ? prefix : name + ".", out);
        } else if constexpr (std::is_base_of_v<Eigen::EigenBase<M>, M>) {
          if (x != y) {
            std::ostringstream s;
            s << name << ": (" << x.transpose() << ") vs (" << y.transpose() << ")\n";
            out += s.str();
          }
        } else if constexpr (std::is_enum_v<M>) {
          if (x != y) out += name + ": " + std::to_string(static_cast<int>(x)) + " vs " + std::to_string(static_cast<int>(y)) + "\n";
        } else if constexpr (std::is_arithmetic_v<M>) {
          if (x != y) {
            std::ostringstream s;
            s.precision(17);
            s << name << ": " << +x << " vs " << +y << "\n";
            out += s.str();
          }
        }
      },
      a, b);
}

template <class Config>
std::string differences(const Config& a, const Config& b) {
  std::string out;
  differences(a, b, "", out);
  return out;
}

// The names of the differing fields, one per line.
std::string names_of(const std::string& differences) {
  std::istringstream in(differences);
  std::string out;
  for (std::string line; std::getline(in, line);) out += line.substr(0, line.find(':')) + "\n";
  return out;
}

// SeekerExample (2 kHz tick, ideal pickoffs and torquers, a wide stop: what the component's
// tests, the firmware images and the model-validity tool fly) and scenarios/seeker_slew.json
// (1 kHz, the device's imperfections, the thresholds the fault campaign derived: what the
// campaigns and the docs' figures fly) share the rotor and the gimbal and differ in these
// fields alone: the file builds on the example ("example": "seeker") and holds these changes.
// A change to either that moves another field apart fails here.
TEST(SeekerExample, GivenSeekerSlewJsonThenItDiffersFromTheExampleOnlyInTheseFields) {
  using S = SeekerExample<double>;
  const Scenario s = load_scenario(kExampleScenarios / "seeker_slew.json");
  EXPECT_EQ(names_of(differences(s.component, S::component())),
            "tick_s\nmin_spin_hz\nmax_torque\ngimbal_cone_limit_rad\ngimbal_stop_margin_rad\npickoff_range_rad\n"
            "estimator_gain\nresidual_limit_rad\ntorquer_fail_persistence_ticks\nuncage_settle_ticks\n");
  // (The rings' inertias differ in their last bit: the example computes them from J and A.)
  EXPECT_EQ(names_of(differences(s.gyro, S::stub())),
            "gyro.gimbal_cone_limit_rad\ngyro.max_pitch_rate_rad_s\ngyro.max_yaw_rate_rad_s\ngimbal_stop_rad\n"
            "gimbal.inner_gimbal_inertia\ngimbal.outer_gimbal_inertia\ngimbal.inner_coulomb_torque\n"
            "gimbal.outer_coulomb_torque\ngimbal.mass_unbalance\ngimbal.stop_cone_rad\ngimbal.max_body_rate_rad_s\n"
            "tick_s\npickoff.lsb_rad\npickoff.bias_rad\npickoff.lag_s\npickoff.noise_rad\n"
            "pickoff.range_rad\ntorquer.scale_factor\ntorquer.max_torque\nseed\n");
  // The rotor and the gimbal's make-up are the same.
  EXPECT_EQ(s.gyro.gyro.pitch_inertia, S::kJ);
  EXPECT_EQ(s.gyro.gyro.spin_inertia, S::kJ0);
  EXPECT_EQ(s.gyro.gyro.friction, S::kFriction);
  EXPECT_EQ(s.gyro.spin_hz, S::kSpinHz);
  EXPECT_EQ(s.gyro.gimbal.rotor_transverse_inertia, S::gimbal().rotor_transverse_inertia);
}

TEST(ReportExample, GivenReportSampleJsonThenItsGyroIsTheReportSample) {
  const Scenario s = load_scenario(kExampleScenarios / "report_sample.json");
  EXPECT_EQ(differences(s.gyro.gyro, ReportSample<double>::config()), "");
  EXPECT_EQ(s.gyro.spin_hz, ReportSample<double>::kSpinHz);
}

TEST(ExampleSections, GivenAnExampleWrittenAsScenarioSectionsThenTheyReadBackAsIt) {
  using S = SeekerExample<double>;
  SimulatedGyroConfig<double> stub = S::stub();
  stub.faults[0] = {FaultKind::kBiasJump, 600, 0, 1, 0.01};
  stub.faults[1] = {FaultKind::kDropout, 700, 20, -1, 0.0};
  const Scenario g = parse_gyro_section(gyro_section(stub, 2), S::kTick, "example", "gyro");
  EXPECT_EQ(differences(g.gyro, stub), "");
  EXPECT_EQ(g.fault_count, 2u);
  const Scenario c = parse_component_section(component_section(S::component()), S::kTick, "example", "component");
  EXPECT_EQ(differences(c.component, S::component()), "");
}

}  // namespace
}  // namespace gyro::sil
