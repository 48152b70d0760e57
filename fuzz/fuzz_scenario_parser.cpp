// Fuzz target: gyro_sil's scenario parser (apps/scenario.cpp) on arbitrary bytes.
//
// parse_scenario either returns a Scenario or throws ScenarioError naming file, field and
// reason; any other exception, a crash or undefined behaviour is a defect. An accepted
// scenario must also hold what the parser promises (a positive finite tick, 1..1e8 ticks,
// the schedule in time order, at most kMaxFaultEvents faults). It then goes through the
// configuration check of the stub and the component (check_configs: ScenarioError or
// nothing), and, configured, through the first few ticks of the SIL run (ScenarioError or
// RunError or a summary), so values the parser let through reach the stub and the component.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>
#include <string_view>

#include "fuzz_support.hpp"
#include "scenario.hpp"
#include "sil_runner.hpp"

namespace {

constexpr std::uint64_t kRunTicks = 16;

std::FILE* null_sink() {
  static std::FILE* f = std::fopen("/dev/null", "wb");
  return f;
}

void check_scenario(const gyro::sil::Scenario& s) {
  GYRO_FUZZ_CHECK(s.file == "fuzz.json");
  GYRO_FUZZ_CHECK(s.run.tick_s > 0.0);
  GYRO_FUZZ_CHECK(s.run.ticks >= 1u && s.run.ticks <= 100'000'000u);
  GYRO_FUZZ_CHECK(s.fault_count <= static_cast<std::size_t>(gyro::kMaxFaultEvents));
  for (std::size_t i = 1; i < s.guidance.size(); ++i) {
    GYRO_FUZZ_CHECK(s.guidance[i - 1].t_s <= s.guidance[i].t_s);
    GYRO_FUZZ_CHECK(s.guidance[i - 1].tick <= s.guidance[i].tick);
  }
  for (const gyro::sil::GuidanceEvent& e : s.guidance) {
    GYRO_FUZZ_CHECK(e.t_s >= 0.0 && std::isfinite(e.t_s));
  }
}

void check_error(const gyro::sil::ScenarioError& e) {
  GYRO_FUZZ_CHECK(e.file() == "fuzz.json");
  GYRO_FUZZ_CHECK(!e.field().empty());
  GYRO_FUZZ_CHECK(!e.reason().empty());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  gyro::sil::Scenario s;
  try {
    s = gyro::sil::parse_scenario(text, "fuzz.json");
  } catch (const gyro::sil::ScenarioError& e) {
    check_error(e);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "parse_scenario threw %s\n", e.what());
    GYRO_FUZZ_FAIL("parse_scenario threw something other than ScenarioError");
  } catch (...) {
    GYRO_FUZZ_FAIL("parse_scenario threw a non-standard exception");
  }
  check_scenario(s);

  try {
    gyro::sil::check_configs(s);
  } catch (const gyro::sil::ScenarioError& e) {
    check_error(e);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "check_configs threw %s\n", e.what());
    GYRO_FUZZ_FAIL("check_configs threw something other than ScenarioError");
  }

  s.run.ticks = std::min(s.run.ticks, kRunTicks);
  std::FILE* sink = null_sink();
  GYRO_FUZZ_CHECK(sink != nullptr);
  try {
    gyro::sil::CsvWriter csv(sink);
    gyro::sil::RunOptions options;
    options.progress = false;
    const gyro::sil::RunSummary sum = gyro::sil::run_scenario(s, csv, options);
    GYRO_FUZZ_CHECK(sum.rows == s.run.ticks + 1u);
  } catch (const gyro::sil::ScenarioError& e) {
    check_error(e);
  } catch (const gyro::sil::RunError&) {
    // the stub or the component refused a value the configuration let through: reported
  } catch (const std::exception& e) {
    std::fprintf(stderr, "run_scenario threw %s\n", e.what());
    GYRO_FUZZ_FAIL("run_scenario threw something other than ScenarioError or RunError");
  }
  return 0;
}
