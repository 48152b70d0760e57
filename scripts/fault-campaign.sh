#!/usr/bin/env bash
# Regenerates docs/fault-campaign.md: 500 calibration, 1,000 fault-free and 1,000 fault runs.
# Usage: scripts/fault-campaign.sh [runs] [seed]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset host >/dev/null
cmake --build --preset host --target gyro_fault_campaign
build/host/tools/gyro_fault_campaign scenarios/seeker_slew.json "${1:-1000}" "${2:-1}" \
  --markdown docs/fault-campaign.md
