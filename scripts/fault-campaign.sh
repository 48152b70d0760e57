#!/usr/bin/env bash
# Regenerates docs/fault-campaign.md with gyro_campaign: campaigns/seeker_faults.json (2,000
# runs: 1,000 without a fault, about 143 of each fault kind) on every core.
# Usage: scripts/fault-campaign.sh [gyro_campaign options, e.g. -j 4]
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=(-j "$(nproc)")
[ $# -gt 0 ] && jobs=("$@")
exec scripts/campaign-report.sh campaigns/seeker_faults.json campaigns/seeker_faults.md.in \
  docs/fault-campaign.md docs/img/fault-campaign "${jobs[@]}"
