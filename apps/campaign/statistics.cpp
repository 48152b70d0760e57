#include "statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gyro::campaign {

Bounds wilson_interval(std::uint64_t k, std::uint64_t n, double z) {
  if (n == 0) return {0, 1};
  const double nd = static_cast<double>(n);
  const double p = static_cast<double>(k) / nd;
  const double z2 = z * z;
  const double denom = 1 + z2 / nd;
  const double centre = (p + z2 / (2 * nd)) / denom;
  const double half = z / denom * std::sqrt(p * (1 - p) / nd + z2 / (4 * nd * nd));
  // At k = 0 and k = n the bound on the observed side is exactly 0 (or 1).
  return {k == 0 ? 0.0 : std::max(0.0, centre - half), k == n ? 1.0 : std::min(1.0, centre + half)};
}

double percentile(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return std::numeric_limits<double>::quiet_NaN();
  const double rank = std::ceil(p * static_cast<double>(sorted.size()));
  const std::size_t i = rank < 1 ? 0 : static_cast<std::size_t>(rank) - 1;
  return sorted[std::min(i, sorted.size() - 1)];
}

}  // namespace gyro::campaign
