// Fuzz target: gyro_campaign's campaign-file parser (apps/campaign/campaign_file.cpp) on
// arbitrary bytes, a base scenario given as a path read relative to campaigns/ (so the
// shipped campaigns' "../scenarios/..." resolve).
//
// parse_campaign either returns a Campaign or throws CampaignError naming the file, the field
// and the reason; any other exception, a crash or undefined behaviour is a defect. An accepted
// campaign must hold what the parser promises: 1..kMaxRuns runs, a resolved text within
// kMaxCampaignBytes, finite increasing running sums of choice and fault weights within their
// bounds, ordered uniform and integer ranges. Its first and last runs are then planned twice
// each: plan_run is a pure function of (campaign, run index), so both plans are the same.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

#include "campaign_error.hpp"
#include "campaign_file.hpp"
#include "fuzz_support.hpp"
#include "run_plan.hpp"

namespace {

namespace campaign = gyro::campaign;

void check_sums(const std::vector<double>& cumulative) {
  double last = 0.0;
  for (double w : cumulative) {
    GYRO_FUZZ_CHECK(std::isfinite(w));
    GYRO_FUZZ_CHECK(w > last);
    last = w;
  }
}

void check_campaign(const campaign::Campaign& c) {
  GYRO_FUZZ_CHECK(c.file == "fuzz.json");
  GYRO_FUZZ_CHECK(c.runs >= 1u && c.runs <= campaign::kMaxRuns);
  GYRO_FUZZ_CHECK(c.resolved_text.size() <= campaign::kMaxCampaignBytes);
  GYRO_FUZZ_CHECK(c.tick_s > 0.0 && std::isfinite(c.tick_s));
  for (const campaign::Dispersion& d : c.dispersions) {
    GYRO_FUZZ_CHECK(!d.path.empty());
    switch (d.distribution) {
      case campaign::Distribution::kUniform:
        GYRO_FUZZ_CHECK(d.min <= d.max);
        break;
      case campaign::Distribution::kUniformInteger:
        GYRO_FUZZ_CHECK(d.int_min <= d.int_max);
        break;
      case campaign::Distribution::kChoice:
        GYRO_FUZZ_CHECK(!d.values.empty());
        GYRO_FUZZ_CHECK(d.cumulative_weights.size() == d.values.size());
        check_sums(d.cumulative_weights);
        break;
      case campaign::Distribution::kNormal:
      case campaign::Distribution::kTruncatedNormal:
        GYRO_FUZZ_CHECK(std::isfinite(d.mean) && std::isfinite(d.sd) && d.sd >= 0.0);
        break;
    }
  }
  if (c.faults) {
    GYRO_FUZZ_CHECK(!c.faults->options.empty());
    std::uint64_t total = 0;
    for (const campaign::FaultOption& o : c.faults->options) total += o.weight;
    GYRO_FUZZ_CHECK(total <= campaign::kMaxWeightTotal);
    if (c.faults->cycle) GYRO_FUZZ_CHECK(c.faults->pattern.size() == total);
    check_sums(c.faults->cumulative_weights);
  }
}

void check_plans(const campaign::Campaign& c) {
  for (const std::uint64_t k : {std::uint64_t{0}, c.runs - 1u}) {
    const campaign::RunPlan a = campaign::plan_run(c, k);
    const campaign::RunPlan b = campaign::plan_run(c, k);
    GYRO_FUZZ_CHECK(a.index == k && a.seed == b.seed);
    GYRO_FUZZ_CHECK(a.values.size() == c.dispersions.size());
    GYRO_FUZZ_CHECK(a.scenario.dump() == b.scenario.dump());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  campaign::Campaign c;
  try {
    c = campaign::parse_campaign(text, "fuzz.json", GYRO_CAMPAIGNS_DIR);
  } catch (const campaign::CampaignError& e) {
    GYRO_FUZZ_CHECK(!e.file().empty() && !e.field().empty() && !e.reason().empty());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "parse_campaign threw %s\n", e.what());
    GYRO_FUZZ_FAIL("parse_campaign threw something other than CampaignError");
  } catch (...) {
    GYRO_FUZZ_FAIL("parse_campaign threw a non-standard exception");
  }
  check_campaign(c);
  try {
    check_plans(c);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "plan_run threw %s\n", e.what());
    GYRO_FUZZ_FAIL("an accepted campaign could not be planned");
  }
  return 0;
}
