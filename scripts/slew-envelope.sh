#!/usr/bin/env bash
# Regenerates docs/slew-envelope.md with gyro_campaign: campaigns/seeker_slew_envelope.json
# (2,000 slews over the envelope) on every core.
# Usage: scripts/slew-envelope.sh [gyro_campaign options, e.g. -j 4]
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=(-j "$(nproc)")
[ $# -gt 0 ] && jobs=("$@")
exec scripts/campaign-report.sh campaigns/seeker_slew_envelope.json campaigns/seeker_slew_envelope.md.in \
  docs/slew-envelope.md docs/img/slew-envelope "${jobs[@]}"
