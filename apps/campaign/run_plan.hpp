// One run of a campaign, planned: its seed, the value drawn for every dispersion, the fault
// injected, and the scenario document they make. A pure function of (campaign, run index):
// every random number comes from the counter-based streams of gyro/noise.hpp keyed by the
// run's seed, so a run is the same whichever thread, rank or shard plans it, and alone.
//
//   run seed        = noise_stream_key(campaign seed, run index)
//   dispersion i    : stream (run seed, fnv1a64("dispersion:" + path)); sample 0 (uniform,
//                     normal, choice), samples 0, 1, ... until one falls in the window
//                     (truncated normal)
//   fault injection : streams (run seed, fnv1a64("fault_injection.<field>"))
//   gyro.seed       = the run seed (the stub's pickoff noise)
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "campaign_file.hpp"

namespace gyro::campaign {

struct FaultDraw {
  std::size_t option{0};            // index into fault_injection.faults
  std::optional<FaultKind> kind;    // nullopt: no fault
  double start_s{0};
  double duration_s{0};
  int axis{-1};
  std::optional<double> magnitude;
};

struct RunPlan {
  std::uint64_t index{0};
  std::uint64_t seed{0};
  std::vector<nlohmann::json> values;   // one per dispersion, as set in the scenario
  std::optional<FaultDraw> fault;       // when the campaign injects faults
  nlohmann::json scenario;              // the base with the values and the fault applied
};

[[nodiscard]] std::uint64_t run_seed(std::uint64_t campaign_seed, std::uint64_t run_index) noexcept;

// The value dispersion `d` takes in the run with seed `seed`, given the base value there.
[[nodiscard]] nlohmann::json draw(const Dispersion& d, const nlohmann::json& base_value, std::uint64_t seed);

[[nodiscard]] RunPlan plan_run(const Campaign& c, std::uint64_t run_index);

}  // namespace gyro::campaign
