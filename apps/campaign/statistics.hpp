// The statistics a campaign summary reports: proportions with confidence intervals and
// percentiles.
#pragma once

#include <cstdint>
#include <vector>

namespace gyro::campaign {

struct Bounds {
  double lo{0}, hi{0};
};

// Wilson score interval of a proportion k/n at the normal quantile z (1.96: 95 %). Unlike the
// normal approximation it stays inside [0, 1] and is not empty at k = 0 or k = n: 0 of 1000
// gives [0, 0.38 %]. n = 0 gives [0, 1].
[[nodiscard]] Bounds wilson_interval(std::uint64_t k, std::uint64_t n, double z = 1.959963984540054);

// The nearest-rank percentile p (0 < p <= 1) of sorted values: the smallest value with at
// least a share p of the values at or below it. Empty input: NaN.
[[nodiscard]] double percentile(const std::vector<double>& sorted, double p);

}  // namespace gyro::campaign
