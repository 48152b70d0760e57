// A scenario that builds on an example gyro or on another scenario file (apps/scenario_base.hpp):
// the example's sections under the file's, merged as a JSON merge patch; bases read bounded,
// chains bounded; each refusal names the key.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "gyro/report_sample.hpp"
#include "gyro/seeker_example.hpp"
#include "scenario.hpp"
#include "scenario_base.hpp"

namespace gyro::sil {
namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

const fs::path kScenarios = fs::path(GYRO_SOURCE_DIR) / "scenarios";

// The sections a scenario needs besides the gyro's and the component's.
json flight(double rate_hz) {
  return {{"run", {{"rate_hz", rate_hz}, {"ticks", 10}}},
          {"body", {{"rate_rad_s", {0.0, 0.0, 0.0}}}},
          {"guidance", {{"schedule", {{{"t_s", 0.0}, {"request", "uncage"}}}}}}};
}

Scenario parse(const json& doc) { return parse_scenario(doc.dump(), "t.json"); }

// The field and reason of the refusal `doc` meets ("" if none).
std::string refusal(const json& doc, const std::string& file = "t.json") {
  try {
    (void)parse_scenario(doc.dump(), file);
  } catch (const ScenarioError& e) {
    return e.field() + ": " + e.reason();
  }
  return "";
}

class ScratchDir {
 public:
  ScratchDir() : root_(fs::temp_directory_path() / ("gyro_scenario_base_" + std::to_string(::getpid()))) {
    fs::create_directories(root_);
  }
  ~ScratchDir() { fs::remove_all(root_); }
  fs::path write(const std::string& name, const json& doc) const {
    std::ofstream(root_ / name) << doc.dump(2);
    return root_ / name;
  }

 private:
  fs::path root_;
};

TEST(ScenarioExample, GivenTheSeekerExampleThenItFliesSeekerExampleAsDefined) {
  using S = SeekerExample<double>;
  json doc = flight(1.0 / S::kTick);
  doc["example"] = "seeker";
  const Scenario s = parse(doc);
  EXPECT_EQ(component_section(s.component), component_section(S::component()));
  // The stub's fields the scenario schema has, as the example sets them.
  EXPECT_EQ(gyro_section(s.gyro, 0)["rotor"], gyro_section(S::stub(), 0)["rotor"]);
  EXPECT_EQ(gyro_section(s.gyro, 0)["limits"], gyro_section(S::stub(), 0)["limits"]);
  EXPECT_EQ(gyro_section(s.gyro, 0)["gimbal"], gyro_section(S::stub(), 0)["gimbal"]);
}

TEST(ScenarioExample, GivenTheReportExampleThenItFliesTheReportsRotor) {
  using R = ReportSample<double>;
  json doc = flight(2828);
  doc["example"] = "report";
  doc["component"] = (*read_scenario(kScenarios / "report_sample.json").document)["component"];
  const Scenario s = parse(doc);
  EXPECT_EQ(s.gyro.plant, PlantKind::kReport);
  EXPECT_EQ(s.gyro.gyro.pitch_inertia, R::config().pitch_inertia);
  EXPECT_EQ(s.gyro.gyro.yaw_inertia, R::config().yaw_inertia);
  EXPECT_EQ(s.gyro.gyro.friction, R::config().friction);
  EXPECT_EQ(s.gyro.gyro.gravity, R::config().gravity);
  EXPECT_EQ(s.gyro.spin_hz, R::kSpinHz);
}

TEST(ScenarioExample, GivenADerivedFieldThenTheExampleLeavesItToFollow) {
  const json g = example_sections("seeker", "t.json")["gyro"];
  EXPECT_FALSE(g["gimbal"].contains("inner_friction"));
  json doc = flight(2000);
  doc["example"] = "seeker";
  doc["gyro"] = {{"rotor", {{"friction", 5e-4}}}};
  const Scenario s = parse(doc);
  EXPECT_EQ(s.gyro.gimbal.inner_friction, 5e-4);  // the bearings follow the rotor's friction
  EXPECT_EQ(s.gyro.gimbal.outer_friction, 5e-4);
}

TEST(ScenarioExample, GivenChangesThenTheyMergeOverTheExample) {
  json doc = flight(2000);
  doc["example"] = "seeker";
  doc["component"] = {{"max_torque", 0.05}};
  doc["gyro"] = {{"pickoff", {{"bias_rad", {1e-4, 0.0}}}}, {"gimbal", {{"max_torque", nullptr}}}};
  const Scenario s = parse(doc);
  EXPECT_EQ(s.component.max_torque, 0.05);
  EXPECT_EQ(s.component.residual_limit_rad, SeekerExample<double>::component().residual_limit_rad);
  EXPECT_EQ(s.gyro.pickoff.bias_rad[0], 1e-4);
  EXPECT_EQ(s.gyro.gimbal.max_torque, 1e3);  // null: the scenario's default, not the example's 1
}

TEST(ScenarioExample, GivenAnUnknownExampleThenRefusedNamingTheKnownOnes) {
  json doc = flight(2000);
  doc["example"] = "seker";
  EXPECT_EQ(refusal(doc), "example: unknown example \"seker\" (one of: seeker, report)");
  doc["example"] = 1;
  EXPECT_EQ(refusal(doc), "example: expected a string, got number");
}

TEST(ScenarioBase, GivenABaseFileThenTheFileChangesIt) {
  const ScratchDir dir;
  json base = flight(2000);
  base["example"] = "seeker";
  base["description"] = "base";
  dir.write("base.json", base);
  const fs::path top = dir.write("top.json", {{"base", "base.json"}, {"component", {{"max_torque", 0.07}}}});
  const Scenario s = read_scenario(top);
  EXPECT_EQ(s.component.max_torque, 0.07);
  EXPECT_EQ(s.description, "base");
  EXPECT_EQ(s.run.ticks, 10u);
}

TEST(ScenarioBase, GivenACycleThenRefusedAfterTheLongestChain) {
  const ScratchDir dir;
  dir.write("a.json", {{"base", "b.json"}});
  const fs::path b = dir.write("b.json", {{"base", "a.json"}});
  try {
    (void)read_scenario(b);
    FAIL() << "a cycle of bases was read";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.field(), "base");
    EXPECT_EQ(e.reason(), "more than 4 bases in a chain (or a cycle)");
  }
}

TEST(ScenarioBase, GivenAMissingBaseThenRefusedNamingIt) {
  const ScratchDir dir;
  const fs::path top = dir.write("top.json", {{"base", "none.json"}});
  try {
    (void)read_scenario(top);
    FAIL() << "a missing base was read";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.field(), "base");
    EXPECT_NE(e.reason().find("none.json"), std::string::npos) << e.reason();
  }
}

TEST(ScenarioBase, GivenBothAnExampleAndABaseThenRefused) {
  json doc = flight(2000);
  doc["example"] = "seeker";
  doc["base"] = "seeker_slew.json";
  EXPECT_EQ(refusal(doc), "base: a scenario builds on an example or on a base scenario, not both");
}

TEST(ScenarioBase, GivenEachFaultScenarioThenItIsSeekerSlewWithItsChanges) {
  const Scenario slew = read_scenario(kScenarios / "seeker_slew.json");
  for (const char* name : {"fault_bias_jump.json", "fault_dead_torquer.json", "fault_stuck_pickoff.json"}) {
    const Scenario f = read_scenario(kScenarios / name);
    EXPECT_EQ(gyro_section(f.gyro, 0), gyro_section(slew.gyro, 0)) << name;  // the faults aside
    EXPECT_EQ(f.gyro.gimbal.inner_gimbal_inertia, slew.gyro.gimbal.inner_gimbal_inertia) << name;
    EXPECT_EQ(f.fault_count, 1u) << name;
  }
}

}  // namespace
}  // namespace gyro::sil
