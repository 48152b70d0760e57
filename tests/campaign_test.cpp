// gyro_campaign's library: campaign files and their refusals (case by case), the
// counter-based draws (per run, per field, independent of order), the distributions'
// statistics, the metrics against the time history, the per-run table and the statistics of
// the summary.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "campaign_error.hpp"
#include "campaign_file.hpp"
#include "campaign_run.hpp"
#include "json_path.hpp"
#include "option_values.hpp"
#include "output_dir.hpp"
#include "run_plan.hpp"
#include "run_pool.hpp"
#include "run_table.hpp"
#include "sil_runner.hpp"
#include "statistics.hpp"

namespace gyro::campaign {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

const fs::path kSource = GYRO_SOURCE_DIR;

// A valid campaign on the seeker scenario; each refusal case below breaks one thing in it.
json valid_campaign() {
  return json::parse(R"({
    "description": "test",
    "base": "scenarios/seeker_slew.json",
    "runs": 10,
    "seed": 3,
    "dispersions": [
      { "path": "gyro.rotor.friction", "distribution": "uniform", "min": 0.9, "max": 1.1, "apply": "scale" },
      { "path": "gyro.pickoff.bias_rad[1]", "distribution": "normal", "mean": 0.0, "sd": 1e-4 },
      { "path": "component.uncage_settle_ticks", "distribution": "uniform_integer", "min": 40, "max": 60 }
    ],
    "fault_injection": { "faults": [
      { "kind": "none" },
      { "kind": "bias_jump", "start_s": [0.6, 0.9], "magnitude": [0.002, 0.02], "sign": "either" }
    ] },
    "metrics": { "healthy_residual": true, "safe_mode": true, "final_mode": true,
                 "slew_rate_error": { "from_s": 0.7, "to_s": 1.0 } },
    "criteria": [ { "metric": "latency_s", "max": 0.1, "runs": "faulted" } ]
  })");
}

Campaign parse(const json& j) { return parse_campaign(j.dump(2), "c.json", kSource); }
Campaign parse_text(const std::string& text) { return parse_campaign(text, "c.json", kSource); }

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// ---------------------------------------------------------------------------------------
// Refusals, case by case

struct BadCase {
  const char* name;
  std::function<void(json&)> change;
  const char* field;
  const char* reason;  // a part of the reason
};

TEST(CampaignFile, GivenTheValidCampaignThenItIsAccepted) {
  const Campaign c = parse(valid_campaign());
  EXPECT_EQ(c.runs, 10u);
  EXPECT_EQ(c.seed, 3u);
  ASSERT_EQ(c.dispersions.size(), 3u);
  EXPECT_EQ(c.dispersions[1].path, "gyro.pickoff.bias_rad[1]");
  ASSERT_TRUE(c.faults.has_value());
  EXPECT_EQ(c.faults->pattern, (std::vector<std::size_t>{0, 1}));
  EXPECT_EQ(c.ticks, 1500u);
  EXPECT_EQ(c.criteria.front().label, "latency_s <= 0.1 (runs with an injected fault)");
}

TEST(CampaignFile, GivenEachMalformedCampaignThenItIsRefusedNamingFieldAndReason) {
  const std::vector<BadCase> cases = {
      // the top level
      {"unknown top key", [](json& j) { j["dispersion"] = json::array(); }, "dispersion",
       "unknown key (did you mean \"dispersions\"?)"},
      {"an empty key", [](json& j) { j[""] = "valun"; }, "[\"\"]", "unknown key"},
      {"no base", [](json& j) { j.erase("base"); }, "base", "missing required field"},
      {"base not a scenario", [](json& j) { j["base"] = 5; }, "base", "expected a scenario file's path or a scenario object"},
      {"base file missing", [](json& j) { j["base"] = "scenarios/none.json"; }, "base",
       "the base scenario \"scenarios/none.json\": cannot open the file for reading"},
      {"base inline and wrong", [](json& j) {
         j["base"] = json::parse(slurp(kSource / "scenarios/seeker_slew.json"));
         j["base"]["gyro"]["gimbal"]["rotor_transverse_inertia"] = -1.6e-5;
       }, "base.gyro.gimbal.rotor_transverse_inertia", "refused by SimulatedGyro::configure"},
      {"base inline, unknown key", [](json& j) {
         j["base"] = json::parse(slurp(kSource / "scenarios/seeker_slew.json"));
         j["base"]["body"]["rate_rads"] = 1;
       }, "base.body.rate_rads", "unknown key (did you mean \"rate_rad_s\"?)"},
      {"no runs", [](json& j) { j.erase("runs"); }, "runs", "missing required field"},
      {"zero runs", [](json& j) { j["runs"] = 0; }, "runs", "must be an integer in [1, 1000000], got 0"},
      {"negative runs", [](json& j) { j["runs"] = -5; }, "runs", "must be an integer in [1, 1000000], got -5"},
      {"too many runs", [](json& j) { j["runs"] = 1000001; }, "runs", "must be an integer in [1, 1000000], got 1000001"},
      {"runs 1e8", [](json& j) { j["runs"] = 100000000; }, "runs", "must be an integer in [1, 1000000], got 100000000"},
      {"fractional runs", [](json& j) { j["runs"] = 2.5; }, "runs", "expected an integer, got number 2.5"},
      {"runs as text", [](json& j) { j["runs"] = "10"; }, "runs", "expected an integer, got string \"10\""},
      {"negative seed", [](json& j) { j["seed"] = -1; }, "seed", "must be an integer in [0, 18446744073709551615]"},
      // `set`
      {"set on a missing field", [](json& j) { j["set"] = {{"gyro.rotr.friction", 1.0}}; }, "set.gyro.rotr.friction",
       "no field \"rotr\" in gyro (did you mean \"rotor\"?) in the base scenario"},
      {"set an unknown key", [](json& j) { j["set"] = {{"body.rate_rads", 1.0}}; }, "base",
       "body.rate_rads: unknown key"},
      {"set overlapping", [](json& j) { j["set"] = {{"body.weave", json::object()}, {"body.weave.frequency_hz", 1.0}}; },
       "set.body.weave.frequency_hz", "overlaps set.body.weave"},
      // dispersion paths
      {"path typo", [](json& j) { j["dispersions"][0]["path"] = "gyro.rotor.fricton"; }, "dispersions[0].path",
       "no field \"fricton\" in gyro.rotor (did you mean \"friction\"?) in the base scenario"},
      {"path of an optional field left out", [](json& j) { j["dispersions"][0]["path"] = "gyro.rotor.spin_down_time_constant_s"; },
       "dispersions[0].path", "no field \"spin_down_time_constant_s\" in gyro.rotor"},
      {"path index out of range", [](json& j) { j["dispersions"][1]["path"] = "gyro.pickoff.bias_rad[2]"; },
       "dispersions[1].path", "no element [2]: gyro.pickoff.bias_rad has 2 elements"},
      {"path through a number", [](json& j) { j["dispersions"][0]["path"] = "gyro.rotor.friction.x"; },
       "dispersions[0].path", "gyro.rotor.friction is a number"},
      {"path syntax", [](json& j) { j["dispersions"][0]["path"] = "gyro..rotor"; }, "dispersions[0].path",
       "expected a field name at character 6"},
      {"path bad index", [](json& j) { j["dispersions"][0]["path"] = "gyro.pickoff.bias_rad[x]"; },
       "dispersions[0].path", "expected an index"},
      {"path dispersed twice", [](json& j) { j["dispersions"][2]["path"] = "gyro.rotor.friction"; }, "dispersions[2].path",
       "gyro.rotor.friction is dispersed twice (also dispersions[0].path"},
      {"paths overlapping", [](json& j) {
         j["dispersions"][2] = {{"path", "gyro.rotor"}, {"distribution", "choice"}, {"values", {json::object()}}};
       }, "dispersions[2].path", "overlaps (dispersions[0].path \"gyro.rotor.friction\")"},
      {"the run's seed", [](json& j) { j["dispersions"][2]["path"] = "gyro.seed"; }, "dispersions[2].path",
       "gyro.seed is the run's seed"},
      {"a number distribution on a name", [](json& j) { j["dispersions"][0]["path"] = "run.precision"; },
       "dispersions[0].path", "run.precision is string \"double\", not a number: only \"choice\" can disperse it"},
      {"a real on an integer field", [](json& j) {
         j["dispersions"][2] = {{"path", "component.residual_persistence_ticks"}, {"distribution", "uniform"},
                                {"min", 10}, {"max", 20}};
       }, "dispersions[2].distribution", "takes an integer: disperse it with \"uniform_integer\" or \"choice\""},
      // distributions
      {"unknown distribution", [](json& j) { j["dispersions"][0]["distribution"] = "gauss"; },
       "dispersions[0].distribution", "unknown distribution \"gauss\""},
      {"no distribution", [](json& j) { j["dispersions"][0].erase("distribution"); }, "dispersions[0].distribution",
       "missing required field"},
      {"unknown dispersion key", [](json& j) { j["dispersions"][0]["maximum"] = 1; }, "dispersions[0].maximum",
       "unknown key"},
      {"uniform empty", [](json& j) { j["dispersions"][0]["max"] = 0.9; }, "dispersions[0].max", "must be > min (0.9), got 0.9"},
      {"uniform with sd", [](json& j) { j["dispersions"][0]["sd"] = 1; }, "dispersions[0].sd",
       "not a parameter of distribution \"uniform\""},
      {"normal sd 0", [](json& j) { j["dispersions"][1]["sd"] = 0; }, "dispersions[1].sd", "must be > 0, got 0"},
      {"normal sd not finite", [](json& j) { j["dispersions"][1]["sd"] = "inf"; }, "dispersions[1].sd",
       "expected a number, got string \"inf\""},
      {"truncated normal, window without mass", [](json& j) {
         j["dispersions"][1] = {{"path", "gyro.pickoff.bias_rad[1]"}, {"distribution", "truncated_normal"}, {"mean", 0.0},
                                {"sd", 1e-4}, {"min", 5e-4}, {"max", 6e-4}};
       }, "dispersions[1].min", "less than 0.001"},
      {"truncated normal without bounds", [](json& j) {
         j["dispersions"][1] = {{"path", "gyro.pickoff.bias_rad[1]"}, {"distribution", "truncated_normal"}, {"mean", 0.0},
                                {"sd", 1e-4}};
       }, "dispersions[1].min", "missing required field"},
      {"integer range reversed", [](json& j) { j["dispersions"][2]["max"] = 30; }, "dispersions[2].max",
       "must be >= min (40), got 30"},
      {"integer range of reals", [](json& j) { j["dispersions"][2]["min"] = 40.5; }, "dispersions[2].min",
       "expected an integer, got number 40.5"},
      {"choice without values", [](json& j) {
         j["dispersions"][0] = {{"path", "run.precision"}, {"distribution", "choice"}, {"values", json::array()}};
       }, "dispersions[0].values", "needs at least one value"},
      {"choice weights mismatched", [](json& j) {
         j["dispersions"][0] = {{"path", "run.precision"}, {"distribution", "choice"}, {"values", {"float", "double"}},
                                {"weights", {1}}};
       }, "dispersions[0].weights", "expected 2 weights (one per value), got 1"},
      {"choice weight zero", [](json& j) {
         j["dispersions"][0] = {{"path", "run.precision"}, {"distribution", "choice"}, {"values", {"float", "double"}},
                                {"weights", {1, 0}}};
       }, "dispersions[0].weights[1]", "must be > 0, got 0"},
      {"choice weights whose total overflows", [](json& j) {
         j["dispersions"][0] = {{"path", "run.precision"}, {"distribution", "choice"}, {"values", {"float", "double"}},
                                {"weights", {1e308, 1e308}}};
       }, "dispersions[0].weights", "the weights' total overflows a double at weights[1] (1e+308 after a sum of 1e+308)"},
      {"choice weight lost in the total", [](json& j) {
         j["dispersions"][0] = {{"path", "run.precision"}, {"distribution", "choice"}, {"values", {"float", "double"}},
                                {"weights", {1e300, 1}}};
       }, "dispersions[0].weights[1]", "too small to change the total 1e+300 of the weights before it"},
      {"scale of a name", [](json& j) {
         j["dispersions"][0] = {{"path", "run.precision"}, {"distribution", "choice"}, {"values", {"float"}}, {"apply", "scale"}};
       }, "dispersions[0].apply", "\"scale\" needs a number at run.precision"},
      {"unknown apply", [](json& j) { j["dispersions"][0]["apply"] = "multiply"; }, "dispersions[0].apply",
       "expected \"set\", \"scale\" or \"offset\", got \"multiply\""},
      // fault injection
      {"unknown fault kind", [](json& j) { j["fault_injection"]["faults"][1]["kind"] = "bias_jmp"; },
       "fault_injection.faults[1].kind", "unknown fault kind \"bias_jmp\" (one of: none, stuck_pickoff"},
      {"fault after the run", [](json& j) { j["fault_injection"]["faults"][1]["start_s"] = {0.6, 1.5}; },
       "fault_injection.faults[1].start_s", "at or after the run's end (1.5 s)"},
      {"fault interval reversed", [](json& j) { j["fault_injection"]["faults"][1]["start_s"] = {0.9, 0.6}; },
       "fault_injection.faults[1].start_s", "lo <= hi"},
      {"fault magnitude missing", [](json& j) { j["fault_injection"]["faults"][1].erase("magnitude"); },
       "fault_injection.faults[1].magnitude", "missing required field (needed by kind \"bias_jump\")"},
      {"magnitude on a stuck pickoff", [](json& j) {
         j["fault_injection"]["faults"][1] = {{"kind", "stuck_pickoff"}, {"start_s", 0.6}, {"magnitude", 1}};
       }, "fault_injection.faults[1].magnitude", "kind \"stuck_pickoff\" takes no magnitude"},
      {"fault axis 2", [](json& j) { j["fault_injection"]["faults"][1]["axis"] = {0, 2}; },
       "fault_injection.faults[1].axis[1]", "must be 0 (pitch), 1 (yaw) or -1 (both), got 2"},
      {"no fault with a start", [](json& j) { j["fault_injection"]["faults"][0]["start_s"] = 0.5; },
       "fault_injection.faults[0].start_s", "a run without a fault takes no \"start_s\""},
      {"fault weight 0", [](json& j) { j["fault_injection"]["faults"][0]["weight"] = 0; },
       "fault_injection.faults[0].weight", "must be an integer in [1, 1000000], got 0"},
      {"fault weights above their total's bound", [](json& j) {
         j["fault_injection"]["faults"][0]["weight"] = 1000000;
         j["fault_injection"]["faults"][1]["weight"] = 1000000;
       }, "fault_injection.faults", "the weights total 2000000, more than the limit of 1000000"},
      {"unknown select", [](json& j) { j["fault_injection"]["select"] = "shuffle"; }, "fault_injection.select",
       "expected \"cycle\" or \"random\""},
      {"spin failure with a negative decay", [](json& j) {
         j["fault_injection"]["faults"][1] = {{"kind", "spin_motor_failure"}, {"start_s", 0.6}, {"magnitude", {-0.1, 0.1}}};
       }, "fault_injection.faults[1].magnitude", "decay time constant must be > 0"},
      // metrics
      {"unknown metric", [](json& j) { j["metrics"]["latency"] = true; }, "metrics.latency", "unknown key"},
      {"tracking metric without a track", [](json& j) { j["metrics"]["tracking"] = true; }, "metrics.tracking",
       "the base scenario tracks no line of sight (give it a guidance.track section)"},
      {"window after the end", [](json& j) { j["metrics"]["slew_rate_error"]["to_s"] = 2.0; },
       "metrics.slew_rate_error.to_s", "after the run's end (1.5 s)"},
      {"window reversed", [](json& j) { j["metrics"]["slew_rate_error"]["from_s"] = 1.2; },
       "metrics.slew_rate_error.to_s", "must be >= from_s (1.2)"},
      {"unknown flag", [](json& j) { j["metrics"]["flag_counters"] = {"residual_falt"}; }, "metrics.flag_counters[0]",
       "unknown flag \"residual_falt\" (did you mean \"residual_fault\"?)"},
      // criteria
      {"criterion on no metric", [](json& j) { j["criteria"][0]["metric"] = "latency"; }, "criteria[0].metric",
       "\"latency\" is not a metric this campaign records (did you mean \"latency_s\"?)"},
      {"criterion on a metric not recorded", [](json& j) { j["criteria"][0]["metric"] = "time_at_stop_s"; },
       "criteria[0].metric", "is not a metric this campaign records"},
      {"criterion with two bounds", [](json& j) { j["criteria"][0]["min"] = 0; }, "criteria[0].max",
       "give exactly one of \"max\", \"min\" or \"equals\""},
      {"criterion max on a boolean", [](json& j) { j["criteria"][0] = {{"metric", "detected"}, {"max", 1}}; },
       "criteria[0].max", "detected is not a number: use \"equals\""},
      {"criterion on an unknown mode", [](json& j) { j["criteria"][0] = {{"metric", "final_mode"}, {"equals", "safe"}}; },
       "criteria[0].equals", "unknown mode \"safe\""},
      {"criterion on a kind never injected", [](json& j) { j["criteria"][0]["runs"] = {"dropout"}; },
       "criteria[0].runs[0]", "no run of this campaign injects \"dropout\""},
      {"criterion on faulted runs without faults", [](json& j) { j.erase("fault_injection"); }, "criteria[0].runs",
       "this campaign injects no faults"},
  };
  std::set<std::string> names;
  for (const BadCase& bc : cases) {
    SCOPED_TRACE(bc.name);
    EXPECT_TRUE(names.insert(bc.name).second) << "two cases share a name";
    json j = valid_campaign();
    bc.change(j);
    try {
      (void)parse(j);
      ADD_FAILURE() << "accepted";
    } catch (const CampaignError& e) {
      EXPECT_EQ(e.file(), "c.json");
      EXPECT_EQ(e.field(), bc.field) << e.what();
      EXPECT_NE(e.reason().find(bc.reason), std::string::npos) << e.reason();
      EXPECT_EQ(std::string(e.what()), "c.json: " + e.field() + ": " + e.reason());
    }
  }
}

TEST(CampaignFile, GivenTextThatIsNotJsonOrHasADuplicateKeyThenTheRefusalNamesWhere) {
  const struct {
    const char* text;
    const char* field;
    const char* reason;
  } cases[] = {
      {"{ \"runs\": 10, }", "(document)", "not valid JSON: parse error at line 1"},
      {"{ \"runs\": 10, \"seed\": 1, \"runs\": 20 }", "runs", "duplicate key (a key may appear only once in an object)"},
      {"{ \"dispersions\": [ {}, { \"path\": \"a\", \"min\": 1, \"min\": 2 } ] }", "dispersions[1].min", "duplicate key"},
      {"{ \"base\": { \"gyro\": { \"rotor\": { \"friction\": 1, \"friction\": 2 } } } }", "base.gyro.rotor.friction",
       "duplicate key"},
      {"[1, 2]", "(root)", "expected an object, got an array"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.text);
    try {
      (void)parse_text(c.text);
      ADD_FAILURE() << "accepted";
    } catch (const CampaignError& e) {
      EXPECT_EQ(e.field(), c.field) << e.what();
      EXPECT_NE(e.reason().find(c.reason), std::string::npos) << e.reason();
    }
  }
}

TEST(CampaignFile, GivenABaseScenarioFileWithADuplicateKeyThenItIsRefusedNamingThatFile) {
  const fs::path tmp = fs::temp_directory_path() / ("campaign_test_dup_" + std::to_string(::getpid()) + ".json");
  std::string text = slurp(kSource / "scenarios/seeker_slew.json");
  text.replace(text.find("\"max_torque\": 0.04,"), 0, "\"max_torque\": 1.0, ");
  std::ofstream(tmp) << text;
  json j = valid_campaign();
  j["base"] = tmp.string();
  try {
    (void)parse(j);
    ADD_FAILURE() << "accepted";
  } catch (const CampaignError& e) {
    EXPECT_EQ(e.file(), tmp.string());
    EXPECT_EQ(e.field(), "component.max_torque");
  }
  fs::remove(tmp);
}

TEST(CampaignFile, GivenTheResolvedTextThenItReadsBackToTheSameCampaignAndFingerprint) {
  const Campaign c = parse(valid_campaign());
  const Campaign again = parse_text(c.resolved_text);
  EXPECT_EQ(again.resolved_text, c.resolved_text);
  EXPECT_EQ(again.fingerprint, c.fingerprint);
  EXPECT_EQ(again.base_source, "inline");
  for (std::uint64_t k = 0; k < c.runs; ++k) EXPECT_EQ(plan_run(again, k).scenario, plan_run(c, k).scenario);
}

TEST(CampaignFile, GivenTheShippedCampaignsThenTheyAreAccepted) {
  for (const char* f : {"campaigns/seeker_faults.json", "campaigns/seeker_slew_envelope.json",
                        "tests/data/campaigns/small.json"}) {
    SCOPED_TRACE(f);
    EXPECT_NO_THROW((void)read_campaign(kSource / f));
  }
}

// ---------------------------------------------------------------------------------------
// Bounded inputs

// The refusal `call` throws, or a failure if it throws none.
template <class F>
CampaignError refusal_of(F call) {
  try {
    call();
  } catch (const CampaignError& e) {
    return e;
  }
  ADD_FAILURE() << "accepted";
  return CampaignError("", "", "");
}

TEST(CampaignBounds, GivenDevZeroAsTheCampaignFileThenRefusedNamingItAndTheBoundAfterReadingAtMostThat) {
  const CampaignError e = refusal_of([] { (void)read_campaign("/dev/zero"); });
  EXPECT_EQ(e.file(), "/dev/zero");
  EXPECT_EQ(e.field(), "(file)");
  EXPECT_EQ(e.reason(), "gave more than the limit of " + std::to_string(kMaxCampaignBytes) +
                            " bytes for a campaign file (stopped reading)");
}

TEST(CampaignBounds, GivenACampaignFileLargerThanTheBoundThenRefusedFromItsSizeAlone) {
  const fs::path tmp = fs::temp_directory_path() / ("campaign_test_big_" + std::to_string(::getpid()) + ".json");
  {
    std::ofstream out(tmp);
    out << "{}";
  }
  fs::resize_file(tmp, kMaxCampaignBytes + 1);  // a sparse file: nothing to read needed
  const CampaignError e = refusal_of([&] { (void)read_campaign(tmp); });
  EXPECT_EQ(e.field(), "(file)");
  EXPECT_EQ(e.reason(), "the file has " + std::to_string(kMaxCampaignBytes + 1) + " bytes, more than the limit of " +
                            std::to_string(kMaxCampaignBytes) + " bytes for a campaign file");
  fs::remove(tmp);
}

TEST(CampaignBounds, GivenDevZeroAsTheBaseScenarioThenRefusedNamingItAndTheScenarioBound) {
  json j = valid_campaign();
  j["base"] = "/dev/zero";
  const CampaignError e = refusal_of([&] { (void)parse(j); });
  EXPECT_EQ(e.field(), "base");
  EXPECT_EQ(e.reason(), "the base scenario \"/dev/zero\": gave more than the limit of " +
                            std::to_string(sil::kMaxScenarioBytes) + " bytes for a scenario (stopped reading)");
}

TEST(CampaignBounds, GivenTooManyRunsThenRefusedBeforeTheBaseScenarioIsRead) {
  json j = valid_campaign();
  j["runs"] = kMaxRuns + 1;
  j["base"] = "/dev/zero";  // would be refused too, after reading a megabyte of it
  const CampaignError e = refusal_of([&] { (void)parse(j); });
  EXPECT_EQ(e.field(), "runs");
  EXPECT_EQ(e.reason(), "must be an integer in [1, 1000000], got 1000001");
}

TEST(CampaignBounds, GivenACampaignWhoseResolvedTextExceedsTheBoundThenRefusedSoCampaignJsonReadsBack) {
  json j = valid_campaign();
  j["description"] = std::string(kMaxCampaignBytes, 'x');
  const CampaignError e = refusal_of([&] { (void)parse(j); });
  EXPECT_EQ(e.field(), "(root)");
  EXPECT_NE(e.reason().find("more than the limit of " + std::to_string(kMaxCampaignBytes) + " bytes"),
            std::string::npos) << e.reason();
}

TEST(CampaignBounds, GivenNestingDeeperThanTheBoundThenRefusedWhileParsingNamingWhere) {
  const std::string deep(1'000'000, '[');  // overflowed the stack when copied or dumped
  const CampaignError e = refusal_of([&] { (void)parse_text("{ \"set\": { \"body.weave\": " + deep + " } }"); });
  EXPECT_EQ(e.reason(), "nested deeper than 32 levels");
  std::string path = "set.body.weave";
  for (std::size_t level = 2; level < kMaxCampaignDepth; ++level) path += "[0]";  // root, set, then arrays
  EXPECT_EQ(e.field(), path);
}

TEST(CampaignBounds, GivenOptionCountsThenOnlyDecimalDigitsWithinTheBoundAreAccepted) {
  std::string why;
  EXPECT_EQ(parse_count("-j", "0", 1024, why), 0u);
  EXPECT_EQ(parse_count("-j", "1024", 1024, why), 1024u);
  const struct {
    const char* text;
    const char* why;
  } refused[] = {
      {"", "-j is empty: expected a whole number from 0 to 1024"},
      {"1025", "-j 1025: more than the limit of 1024"},
      {"100000", "-j 100000: more than the limit of 1024"},
      {"99999999999999999999999", "-j 99999999999999999999999: more than the limit of 1024"},
      {"-1", "-j -1: expected a whole number from 0 to 1024"},
      {"+2", "-j +2: expected a whole number from 0 to 1024"},
      {"2.0", "-j 2.0: expected a whole number from 0 to 1024"},
      {"1e3", "-j 1e3: expected a whole number from 0 to 1024"},
      {"nan", "-j nan: expected a whole number from 0 to 1024"},
      {"inf", "-j inf: expected a whole number from 0 to 1024"},
      {" 2", "-j  2: expected a whole number from 0 to 1024"},
      {"2\x1b[2J", "-j 2\\x1b[2J: expected a whole number from 0 to 1024"},
  };
  for (const auto& r : refused) {
    SCOPED_TRACE(r.text);
    why.clear();
    EXPECT_FALSE(parse_count("-j", r.text, 1024, why).has_value());
    EXPECT_EQ(why, r.why);
  }
}

TEST(CampaignBounds, GivenMoreThreadsThanTheBoundThenThePoolRefusesAndGivenMoreThanRunsThenItRunsThem) {
  const Campaign c = parse(valid_campaign());
  EXPECT_THROW(RunPool(c, 0, 2, kMaxThreads + 1), std::invalid_argument);
  RunPool pool(c, 0, 2, kMaxThreads);  // two workers, one a run
  std::size_t rows = 0;
  while (!pool.done()) rows += pool.take(std::chrono::milliseconds(100)).size();
  EXPECT_EQ(rows, 2u);
}

// ---------------------------------------------------------------------------------------
// The output directory: the user's files are safe

class CampaignOutputs : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("campaign_test_out_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::permissions(root_ / "out" / "summary.md", fs::perms::owner_write, fs::perm_options::add, ec);
    fs::remove_all(root_);
  }
  fs::path root_;
};

const std::vector<std::string> kNames = {"runs.csv", "summary.md", "plots/histograms.png", "plots/histograms.dat"};

// The message of the OutputError `call` throws ("" if none).
template <class F>
std::string output_refusal(F call) {
  try {
    call();
  } catch (const OutputError& e) {
    return e.what();
  }
  return "";
}

TEST_F(CampaignOutputs, GivenASymbolicLinkInPlaceOfASubdirectoryThenRefusedAndTheLinkedFileUntouched) {
  {
    const OutputDir out(root_ / "out", {});
    out.claim(kNames);
    out.write("plots/histograms.png", "first");
  }
  fs::create_directories(root_ / "users");
  std::ofstream(root_ / "users" / "histograms.png") << "the user's picture";
  fs::remove_all(root_ / "out" / "plots");
  fs::create_directory_symlink(root_ / "users", root_ / "out" / "plots");
  const OutputDir out(root_ / "out", {});
  const std::string why = output_refusal([&] { out.claim(kNames); });
  EXPECT_NE(why.find("/out/plots\" is a symbolic link: refused, not followed"), std::string::npos) << why;
  EXPECT_NE(output_refusal([&] { out.write("plots/histograms.png", "second"); }), "");
  EXPECT_EQ(slurp(root_ / "users" / "histograms.png"), "the user's picture");
  EXPECT_EQ(std::distance(fs::directory_iterator(root_ / "users"), fs::directory_iterator{}), 1);
}

TEST_F(CampaignOutputs, GivenASymbolicLinkInPlaceOfAnOutputThenRefusedAndTheLinkKept) {
  std::ofstream(root_ / "users.csv") << "the user's table";
  fs::create_directories(root_ / "out");
  {
    const OutputDir out(root_ / "out", {});
    out.claim(kNames);
  }
  fs::create_symlink(root_ / "users.csv", root_ / "out" / "runs.csv");
  const OutputDir out(root_ / "out", {});
  const std::string why = output_refusal([&] { out.write("runs.csv", "rows"); });
  EXPECT_NE(why.find("/out/runs.csv\" is a symbolic link: refused, not followed"), std::string::npos) << why;
  EXPECT_TRUE(fs::is_symlink(root_ / "out" / "runs.csv"));
  EXPECT_EQ(slurp(root_ / "users.csv"), "the user's table");
}

TEST_F(CampaignOutputs, GivenAReadOnlyOutputThenItIsNotReplaced) {
  {
    const OutputDir out(root_ / "out", {});
    out.claim(kNames);
    out.write("summary.md", "kept");
  }
  fs::permissions(root_ / "out" / "summary.md", fs::perms::owner_write | fs::perms::group_write | fs::perms::others_write,
                  fs::perm_options::remove);
  const OutputDir out(root_ / "out", {});
  const std::string why = output_refusal([&] { out.claim(kNames); });
  EXPECT_NE(why.find("/out/summary.md\" is read-only: not replaced"), std::string::npos) << why;
  EXPECT_NE(output_refusal([&] { out.write("summary.md", "replaced"); }), "");
  EXPECT_EQ(slurp(root_ / "out" / "summary.md"), "kept");
}

TEST_F(CampaignOutputs, GivenADirectoryInUseThenASecondIsRefusedAndOnceReleasedItIsFree) {
  std::optional<OutputDir> first(std::in_place, root_ / "out", std::vector<fs::path>{});
  EXPECT_TRUE(fs::exists(root_ / "out" / kLockFile));
  const std::string why = output_refusal([&] { const OutputDir second(root_ / "out", {}); });
  EXPECT_NE(why.find("is in use by another gyro_campaign (process " + std::to_string(::getpid()) + ")"),
            std::string::npos) << why;
  first.reset();
  EXPECT_FALSE(fs::exists(root_ / "out" / kLockFile));
  EXPECT_EQ(output_refusal([&] { const OutputDir again(root_ / "out", {}); }), "");
}

TEST_F(CampaignOutputs, GivenAnOutputWrittenThenItReplacesTheFileAndLeavesNoTemporary) {
  const OutputDir out(root_ / "out", {});
  out.claim(kNames);
  out.write("plots/histograms.dat", "one");
  out.write("plots/histograms.dat", [](std::ostream& f) { f << "two " << 2; });
  EXPECT_EQ(slurp(root_ / "out" / "plots" / "histograms.dat"), "two 2");
  for (const auto& e : fs::recursive_directory_iterator(root_ / "out")) {
    EXPECT_NE(e.path().extension(), ".tmp") << e.path();
  }
}

TEST(CampaignBounds, GivenAMergeInputThatNeverEndsThenReadingStopsAtItsBound) {
  try {
    (void)read_file("/dev/zero", 65536, "a manifest");
    ADD_FAILURE() << "accepted";
  } catch (const OutputError& e) {
    EXPECT_EQ(std::string(e.what()), "/dev/zero: gave more than the limit of 65536 bytes for a manifest (stopped reading)");
  }
}

// ---------------------------------------------------------------------------------------
// JSON paths

TEST(CampaignPath, GivenPathsThenTheyParseAndFormatBack) {
  std::string why;
  for (const char* p : {"a", "gyro.rotor.friction", "guidance.schedule[2].slew_rate_rad_s[0]", "a[0][1].b"}) {
    const auto steps = parse_path(p, why);
    ASSERT_TRUE(steps.has_value()) << p << ": " << why;
    EXPECT_EQ(format_path(*steps), p);
  }
  for (const char* p : {"", ".a", "a.", "a..b", "a[", "a[]", "a[-1]", "a[1", "a b", "a[1]b"}) {
    EXPECT_FALSE(parse_path(p, why).has_value()) << p;
    EXPECT_FALSE(why.empty());
  }
}

// ---------------------------------------------------------------------------------------
// Draws: counter-based, per run and per field

TEST(CampaignDraws, GivenARunThenItsPlanIsTheSameWhateverWasPlannedBefore) {
  const Campaign c = parse(valid_campaign());
  const RunPlan alone = plan_run(c, 7);
  for (std::uint64_t k = 0; k < c.runs; ++k) (void)plan_run(c, k);
  const RunPlan after = plan_run(c, 7);
  EXPECT_EQ(alone.seed, after.seed);
  EXPECT_EQ(alone.scenario, after.scenario);
  EXPECT_EQ(alone.seed, run_seed(3, 7));
  EXPECT_EQ(alone.scenario["gyro"]["seed"].get<std::uint64_t>(), alone.seed);
  EXPECT_NE(plan_run(c, 6).seed, alone.seed);
}

TEST(CampaignDraws, GivenADispersionRemovedOrAddedThenTheOtherFieldsDrawTheSameValues) {
  json j = valid_campaign();
  const Campaign full = parse(j);
  j["dispersions"].erase(0);
  j["dispersions"].push_back({{"path", "body.specific_force[1]"}, {"distribution", "uniform"}, {"min", -1}, {"max", 1}});
  const Campaign changed = parse(j);
  for (std::uint64_t k = 0; k < full.runs; ++k) {
    const RunPlan a = plan_run(full, k), b = plan_run(changed, k);
    EXPECT_EQ(a.values[1], b.values[0]);
    EXPECT_EQ(a.values[2], b.values[1]);
  }
}

TEST(CampaignDraws, GivenADifferentCampaignSeedThenEveryRunDiffers) {
  json j = valid_campaign();
  const Campaign a = parse(j);
  j["seed"] = 4;
  const Campaign b = parse(j);
  for (std::uint64_t k = 0; k < a.runs; ++k) EXPECT_NE(plan_run(a, k).values[0], plan_run(b, k).values[0]);
}

// Many draws of one dispersion (run seeds 0..n-1).
std::vector<json> many(const Dispersion& d, const json& base, int n) {
  std::vector<json> out;
  for (int i = 0; i < n; ++i) out.push_back(draw(d, base, run_seed(11, static_cast<std::uint64_t>(i))));
  return out;
}

Dispersion dispersion_of(const json& spec) {
  json j = valid_campaign();
  j["dispersions"] = json::array({spec});
  j["criteria"] = json::array();
  return parse(j).dispersions.front();
}

constexpr int kDraws = 40000;
// Bounds from the central limit theorem: 4.5 standard errors.
constexpr double kSigmas = 4.5;

double mean_of(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

std::vector<double> numbers(const std::vector<json>& v) {
  std::vector<double> out;
  for (const json& x : v) out.push_back(x.get<double>());
  return out;
}

TEST(CampaignDraws, GivenAUniformThenValuesFillTheIntervalWithItsMeanAndVariance) {
  const Dispersion d = dispersion_of({{"path", "body.specific_force[1]"}, {"distribution", "uniform"}, {"min", -2}, {"max", 6}});
  const std::vector<double> v = numbers(many(d, 5.0, kDraws));
  EXPECT_GE(*std::min_element(v.begin(), v.end()), -2.0);
  EXPECT_LT(*std::max_element(v.begin(), v.end()), 6.0);
  const double sd = 8.0 / std::sqrt(12.0);
  EXPECT_NEAR(mean_of(v), 2.0, kSigmas * sd / std::sqrt(kDraws));
  std::vector<int> deciles(10, 0);
  for (double x : v) ++deciles[static_cast<std::size_t>((x + 2.0) / 0.8)];
  for (int c : deciles) EXPECT_NEAR(c, kDraws / 10, kSigmas * std::sqrt(kDraws * 0.1 * 0.9));
}

TEST(CampaignDraws, GivenANormalThenMeanAndSdMatch) {
  const Dispersion d =
      dispersion_of({{"path", "body.specific_force[1]"}, {"distribution", "normal"}, {"mean", 3}, {"sd", 0.5}});
  const std::vector<double> v = numbers(many(d, 0.0, kDraws));
  EXPECT_NEAR(mean_of(v), 3.0, kSigmas * 0.5 / std::sqrt(kDraws));
  double var = 0;
  for (double x : v) var += (x - 3.0) * (x - 3.0);
  var /= kDraws;
  // The sample variance's standard error is sd^2 sqrt(2/n).
  EXPECT_NEAR(var, 0.25, kSigmas * 0.25 * std::sqrt(2.0 / kDraws));
}

TEST(CampaignDraws, GivenATruncatedNormalThenValuesStayInTheWindowWithTheTruncatedMean) {
  // One-sided window [mean, mean + 2 sd]: the truncated mean is mean + sd (phi(0) - phi(2)) / (Phi(2) - Phi(0)).
  const Dispersion d = dispersion_of({{"path", "body.specific_force[1]"}, {"distribution", "truncated_normal"},
                                      {"mean", 1}, {"sd", 2}, {"min", 1}, {"max", 5}});
  const std::vector<double> v = numbers(many(d, 0.0, kDraws));
  EXPECT_GE(*std::min_element(v.begin(), v.end()), 1.0);
  EXPECT_LE(*std::max_element(v.begin(), v.end()), 5.0);
  const double pi = 3.14159265358979323846;
  const double phi0 = 1 / std::sqrt(2 * pi), phi2 = std::exp(-2.0) / std::sqrt(2 * pi);
  const double mass = 0.5 * std::erf(2 / std::sqrt(2.0));
  const double mean = 1 + 2 * (phi0 - phi2) / mass;
  EXPECT_NEAR(mean_of(v), mean, kSigmas * 2 / std::sqrt(kDraws));
}

TEST(CampaignDraws, GivenAUniformIntegerThenEveryValueComesEquallyOften) {
  const Dispersion d =
      dispersion_of({{"path", "component.uncage_settle_ticks"}, {"distribution", "uniform_integer"}, {"min", 3}, {"max", 7}});
  std::map<std::int64_t, int> count;
  for (const json& x : many(d, 50, kDraws)) {
    ASSERT_TRUE(x.is_number_integer());
    ++count[x.get<std::int64_t>()];
  }
  ASSERT_EQ(count.size(), 5u);
  EXPECT_EQ(count.begin()->first, 3);
  EXPECT_EQ(count.rbegin()->first, 7);
  for (const auto& [value, c] : count) EXPECT_NEAR(c, kDraws / 5, kSigmas * std::sqrt(kDraws * 0.2 * 0.8)) << value;
}

TEST(CampaignDraws, GivenAWeightedChoiceThenFrequenciesFollowTheWeights) {
  const Dispersion d = dispersion_of({{"path", "run.precision"}, {"distribution", "choice"},
                                      {"values", {"double", "float"}}, {"weights", {3, 1}}});
  int floats = 0;
  for (const json& x : many(d, "double", kDraws)) floats += x == "float" ? 1 : 0;
  EXPECT_NEAR(floats, kDraws / 4, kSigmas * std::sqrt(kDraws * 0.25 * 0.75));
}

TEST(CampaignDraws, GivenScaleAndOffsetThenTheBaseValueIsScaledOrShifted) {
  const Dispersion s =
      dispersion_of({{"path", "body.specific_force[1]"}, {"distribution", "choice"}, {"values", {2}}, {"apply", "scale"}});
  EXPECT_EQ(draw(s, 1.5, 1).get<double>(), 3.0);
  const Dispersion o =
      dispersion_of({{"path", "body.specific_force[1]"}, {"distribution", "choice"}, {"values", {2}}, {"apply", "offset"}});
  EXPECT_EQ(draw(o, 1.5, 1).get<double>(), 3.5);
}

TEST(CampaignDraws, GivenFaultsInTurnThenRunKTakesOptionKModuloTheWeightedPattern) {
  json j = valid_campaign();
  j["fault_injection"]["faults"][0]["weight"] = 3;
  const Campaign c = parse(j);
  for (std::uint64_t k = 0; k < 12; ++k) {
    const RunPlan p = plan_run(c, k);
    ASSERT_TRUE(p.fault.has_value());
    EXPECT_EQ(p.fault->option, k % 4 == 3 ? 1u : 0u) << k;
    EXPECT_EQ(p.fault->kind.has_value(), k % 4 == 3);
    if (p.fault->kind) {
      EXPECT_GE(p.fault->start_s, 0.6);
      EXPECT_LE(p.fault->start_s, 0.9);
      EXPECT_GE(std::abs(*p.fault->magnitude), 0.002);
      EXPECT_LE(std::abs(*p.fault->magnitude), 0.02);
      ASSERT_EQ(p.scenario["gyro"]["faults"].size(), 1u);
      EXPECT_EQ(p.scenario["gyro"]["faults"][0]["kind"], "bias_jump");
    } else {
      EXPECT_FALSE(p.scenario["gyro"].contains("faults"));
    }
  }
}

// ---------------------------------------------------------------------------------------
// Runs, metrics and the table

// The first time the CSV's mode column reads `mode`; -1 if never.
double first_time_in(const std::string& csv, const std::string& mode) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    const std::size_t c1 = line.find(','), c2 = line.find(',', c1 + 1);
    if (line.substr(c1 + 1, c2 - c1 - 1) == mode) return std::stod(line.substr(0, c1));
  }
  return -1;
}

TEST(CampaignRun, GivenAFaultScenarioThenTheLatencyIsWhatTheTimeHistoryShows) {
  json j = valid_campaign();
  j["base"] = "scenarios/fault_bias_jump.json";  // 0.01 rad pitch bias jump at 0.6 s
  j["dispersions"] = json::array();
  j.erase("fault_injection");
  j["criteria"] = json::array();
  j["runs"] = 1;
  const Campaign c = parse(j);
  const fs::path tmp = fs::temp_directory_path() / ("campaign_test_" + std::to_string(::getpid()) + ".csv");
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  sil::CsvWriter w(f);
  sil::CsvObserver history(w);
  const RunResult r = execute_run(c, 0, &history);
  std::fclose(f);
  const std::string csv = slurp(tmp);
  fs::remove(tmp);
  ASSERT_EQ(r.status, RunStatus::kOk) << r.reason;
  ASSERT_TRUE(r.metrics.has_value());
  const double safe = first_time_in(csv, "fault");
  ASSERT_GT(safe, 0.6);
  ASSERT_TRUE(r.metrics->safe_mode_s.has_value());
  EXPECT_NEAR(*r.metrics->safe_mode_s, safe, 1e-9);
  EXPECT_NEAR(*r.metrics->latency_s, safe - 0.6, 1e-9);
  EXPECT_EQ(r.metrics->detected, std::optional<bool>(true));
  EXPECT_FALSE(r.metrics->false_alarm);
  EXPECT_EQ(r.metrics->final_mode, GyroMode::kFault);
  // The healthy residual is over free ticks before 0.6 s only: below the limit that latched later.
  ASSERT_TRUE(r.metrics->max_residual_healthy_rad.has_value());
  EXPECT_LT(*r.metrics->max_residual_healthy_rad, 0.005);
}

// Runs campaign `j`'s run 0 with its time history; the CSV's text through `csv`.
RunResult run_with_history(const json& j, std::string& csv) {
  const Campaign c = parse(j);
  const fs::path tmp = fs::temp_directory_path() / ("campaign_test_h_" + std::to_string(::getpid()) + ".csv");
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (f == nullptr) return RunResult{};
  sil::CsvWriter w(f);
  sil::CsvObserver history(w);
  RunResult r = execute_run(c, 0, &history);
  std::fclose(f);
  csv = slurp(tmp);
  fs::remove(tmp);
  return r;
}

// The CSV's rows as columns by name.
std::map<std::string, std::vector<std::string>> columns_of(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::istringstream h(line);
  for (std::string n; std::getline(h, n, ',');) names.push_back(n);
  std::map<std::string, std::vector<std::string>> out;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::size_t i = 0;
    for (std::string cell; std::getline(row, cell, ',') && i < names.size(); ++i) out[names[i]].push_back(cell);
  }
  return out;
}

TEST(CampaignRun, GivenTheEnvelopeAndPersistenceMetricsThenTheyAreWhatTheTimeHistoryShows) {
  // GIVEN the bias-jump scenario (0.01 rad at 0.6 s) whose residual limit is set at 1.5 times
  // the largest healthy residual, so that half the limit is crossed and the limit is not
  json j = valid_campaign();
  j["base"] = "scenarios/fault_bias_jump.json";
  j["dispersions"] = json::array();
  j.erase("fault_injection");
  j["criteria"] = json::array();
  j["runs"] = 1;
  j["metrics"] = {{"healthy_residual", true}, {"residual_persistence", true}, {"envelope", true}, {"safe_mode", true}};
  // (The rate limits cut to 0.1 rad/s, under the 0.3 commanded: the contract holds the
  // residual limit above a tick at the rate limit and 2 pickoff LSBs, 1.2e-4: 1.5 times the
  // healthy residual is ~1.5e-4.)
  // The pickoff noise is 1e-5 rad: the contract holds the limit above 9 sigma of it.
  j["set"] = {{"component.max_pitch_rate_rad_s", 0.1}, {"component.max_yaw_rate_rad_s", 0.1},
              {"gyro.pickoff.noise_rad", 1e-5}};
  std::string csv;
  const RunResult first = run_with_history(j, csv);
  ASSERT_EQ(first.status, RunStatus::kOk) << first.reason;
  const double limit = 1.5 * *first.metrics->max_residual_healthy_rad;
  j["set"]["component.residual_limit_rad"] = limit;

  // WHEN it runs with its time history
  const RunResult r = run_with_history(j, csv);
  ASSERT_EQ(r.status, RunStatus::kOk) << r.reason;
  ASSERT_TRUE(r.metrics.has_value());
  EXPECT_FALSE(r.metrics->false_alarm);

  // THEN the time history, replayed here, gives the same figures: the leaky count (+2 a tick
  // above half the limit, -1 below) over free ticks before 0.6 s, the largest cone over the
  // run and the largest one-tick change of a gimbal angle before 0.6 s
  const auto col = columns_of(csv);
  const std::vector<std::string>& mode = col.at("mode");
  const auto num = [&](const char* name, std::size_t k) { return std::stod(col.at(name)[k]); };
  std::uint64_t fill = 0, peak = 0;
  double cone = 0, step = 0;
  for (std::size_t k = 0; k < mode.size(); ++k) {
    const double t = num("t", k);
    const bool healthy = t < 0.6 - 1e-9;
    if (mode[k] == "free" && healthy) {
      const double res = std::max(std::abs(num("residual_pitch", k)), std::abs(num("residual_yaw", k)));
      fill = res > 0.5 * limit ? fill + 2 : (fill > 0 ? fill - 1 : 0);
      peak = std::max(peak, fill);
    }
    cone = std::max(cone, num("cone_true", k));
    if (healthy && k > 0) {
      step = std::max({step, std::abs(num("gimbal_pitch", k) - num("gimbal_pitch", k - 1)),
                       std::abs(num("gimbal_yaw", k) - num("gimbal_yaw", k - 1))});
    }
  }
  ASSERT_GT(peak, 0u);
  ASSERT_TRUE(r.metrics->half_limit_persistence_ticks.has_value());
  EXPECT_EQ(*r.metrics->half_limit_persistence_ticks, static_cast<double>(peak) / 2.0);
  EXPECT_GT(cone, 0.01);
  EXPECT_NEAR(r.metrics->max_cone_rad, cone, 1e-9 * cone);
  ASSERT_TRUE(r.metrics->max_gimbal_step_rad.has_value());
  EXPECT_GT(step, 0.0);
  // (the CSV keeps 10 digits of each angle: a difference of two of them is good to ~1e-10 rad)
  EXPECT_NEAR(*r.metrics->max_gimbal_step_rad, step, 1e-8 * step + 1e-10);
}

TEST(CampaignRun, GivenAnIntegerDispersionOfACountThenTheRunsRunWithThatCount) {
  // The scenario's counts take non-negative integers only: the draws must reach it as such.
  const Campaign c = parse(valid_campaign());
  for (std::uint64_t k = 0; k < 3; ++k) {
    const RunResult r = execute_run(c, k);
    EXPECT_EQ(r.status, RunStatus::kOk) << r.reason;
    const std::int64_t ticks = r.plan.values[2].get<std::int64_t>();
    EXPECT_GE(ticks, 40);
    EXPECT_LE(ticks, 60);
  }
}

TEST(CampaignRun, GivenADispersedValueTheComponentRefusesThenTheRunIsReportedRefusedWithTheField) {
  json j = valid_campaign();
  j["dispersions"] = json::array({{{"path", "component.estimator_gain"}, {"distribution", "choice"}, {"values", {1.5}}}});
  const Campaign c = parse(j);
  const RunResult r = execute_run(c, 0);
  EXPECT_EQ(r.status, RunStatus::kRefused);
  EXPECT_EQ(r.reason, "component.estimator_gain: input out of range (value 1.5); refused by GyroComponent::configure: "
            "estimator_gain = 1.5 is above its upper bound (1): a fraction of the residual per tick");
  const std::string row = format_row(c, r);
  const std::vector<std::string> cells = *split_csv_line(row.substr(0, row.size() - 1));
  const std::vector<std::string> header = table_header(c);
  ASSERT_EQ(cells.size(), header.size());
  EXPECT_EQ(cells[2], "refused");
  EXPECT_EQ(cells[3], "false");
  EXPECT_EQ(cells.back(), r.reason);
}

TEST(CampaignTable, GivenRowsThenTheyReadBackCellForCell) {
  const Campaign c = parse(valid_campaign());
  std::string text = csv_line(table_header(c)) + "\n";
  for (std::uint64_t k = 0; k < 4; ++k) text += format_row(c, execute_run(c, k));
  const RunTable t = parse_run_table(text, c, "runs.csv");
  ASSERT_EQ(t.size(), 4u);
  std::string again = csv_line(t.header()) + "\n";
  for (std::size_t i = 0; i < t.size(); ++i) {
    std::vector<std::string> cells;
    for (std::size_t col = 0; col < t.header().size(); ++col) cells.push_back(t.text(i, col));
    again += csv_line(cells) + "\n";
  }
  EXPECT_EQ(again, text);
  // Numbers read back to the very doubles written.
  const RunPlan p = plan_run(c, 2);
  EXPECT_EQ(*cell_number(t.cell(2, *t.column("gyro.rotor.friction"))), p.values[0].get<double>());
}

TEST(CampaignTable, GivenAQuotedReasonThenTheTableGivesItsTextAndTheOtherCellsStayInPlace) {
  json j = valid_campaign();
  j["dispersions"] = json::array({{{"path", "component.estimator_gain"}, {"distribution", "choice"}, {"values", {1.5}}}});
  j["set"] = {{"description", "a, b"}};
  const Campaign c = parse(j);
  RunResult r = execute_run(c, 0);
  r.reason = "say \"no\", twice";
  const RunTable t(c, {format_row(c, r)}, "runs.csv");
  const std::size_t reason = *t.column("reason");
  EXPECT_EQ(t.cell(0, reason), "\"say \"\"no\"\", twice\"");
  EXPECT_EQ(t.text(0, reason), "say \"no\", twice");
  EXPECT_EQ(t.cell(0, *t.column("status")), "refused");
  EXPECT_EQ(t.cell(0, 0), "0");
}

TEST(CampaignTable, GivenCellsWithCommasAndQuotesThenTheyAreQuotedAndSplitBack) {
  const std::vector<std::string> cells = {"a", "b,c", "say \"x\"", "", "[1,2]"};
  const std::string line = csv_line(cells);
  EXPECT_EQ(line, "a,\"b,c\",\"say \"\"x\"\"\",,\"[1,2]\"");
  EXPECT_EQ(*split_csv_line(line), cells);
  EXPECT_FALSE(split_csv_line("\"open").has_value());
}

TEST(CampaignTable, GivenATableOfAnotherCampaignOrOutOfRangeRunsThenItIsRefused) {
  const Campaign c = parse(valid_campaign());
  EXPECT_THROW((void)parse_run_table("run,seed\n", c, "runs.csv"), CampaignError);
  const std::string header = csv_line(table_header(c)) + "\n";
  std::string row = format_row(c, execute_run(c, 1));
  row.replace(0, 1, "99");  // run 99 of a 10-run campaign
  EXPECT_THROW((void)parse_run_table(header + row, c, "runs.csv"), CampaignError);
  EXPECT_THROW((void)parse_run_table(header + "1,2\n", c, "runs.csv"), CampaignError);
  EXPECT_THROW((void)parse_run_table(header + "1,\"2\n", c, "runs.csv"), CampaignError);  // quote not closed
  EXPECT_THROW((void)parse_run_table(header.substr(0, header.size() - 1), c, "runs.csv"), CampaignError);
}

// ---------------------------------------------------------------------------------------
// Statistics of the summary

TEST(CampaignStatistics, GivenProportionsThenTheWilsonIntervalMatchesPublishedValues) {
  // Newcombe (1998), Statistics in Medicine 17:857, the worked examples (95 %, the score
  // method without continuity correction): 0/20 -> [0, 0.1611]; 1/29 -> [0.0061, 0.1718];
  // 15/148 -> [0.0624, 0.1605]; 81/263 -> [0.2553, 0.3662]; 29/29 -> [0.8830, 1].
  const struct {
    std::uint64_t k, n;
    double lo, hi;
  } published[] = {{0, 20, 0.0, 0.1611},       {1, 29, 0.0061, 0.1718},  {15, 148, 0.0624, 0.1605},
                   {81, 263, 0.2553, 0.3662}, {29, 29, 0.8830, 1.0}};
  for (const auto& p : published) {
    const Bounds b = wilson_interval(p.k, p.n);
    EXPECT_NEAR(b.lo, p.lo, 5e-5) << p.k << "/" << p.n;
    EXPECT_NEAR(b.hi, p.hi, 5e-5) << p.k << "/" << p.n;
  }
  EXPECT_EQ(wilson_interval(29, 29).hi, 1.0);
  EXPECT_EQ(wilson_interval(0, 20).lo, 0.0);
  const Bounds none = wilson_interval(0, 0);
  EXPECT_EQ(none.lo, 0.0);
  EXPECT_EQ(none.hi, 1.0);
}

TEST(CampaignStatistics, GivenSortedValuesThenPercentilesAreNearestRank) {
  const std::vector<double> v = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  EXPECT_EQ(percentile(v, 0.5), 5);
  EXPECT_EQ(percentile(v, 0.95), 10);
  EXPECT_EQ(percentile(v, 0.1), 1);
  EXPECT_EQ(percentile(v, 0.11), 2);
  EXPECT_EQ(percentile(v, 1.0), 10);
  EXPECT_TRUE(std::isnan(percentile({}, 0.5)));
}

}  // namespace
}  // namespace gyro::campaign
