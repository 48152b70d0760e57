#!/usr/bin/env bash
# Regenerates docs/fault-campaign.md with gyro_campaign: campaigns/seeker_faults.json on the gimbal
# plant (2,100 runs: 1,050 without a fault, 150 of each fault kind; about 20 s on two cores).
# Usage: scripts/fault-campaign.sh [gyro_campaign options, e.g. -j 4]
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=(-j "$(nproc)")
[ $# -gt 0 ] && jobs=("$@")
exec scripts/campaign-report.sh campaigns/seeker_faults.json campaigns/seeker_faults.md.in \
  docs/fault-campaign.md docs/img/fault-campaign "${jobs[@]}"
