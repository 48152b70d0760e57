#!/usr/bin/env bash
# Regenerates docs/stop-protection.md and docs/stop-protection.csv: the flight component
# against the gimbal plant with the body turning the gimbal toward its stop, two gyros, five
# modes (2,970 cases of 3 s of flight: about two minutes of CPU after the build).
# Usage: scripts/stop-envelope.sh [jobs, default 2]
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${1:-2}
scripts/setup.sh
cmake --preset host >/dev/null
cmake --build --preset host --target gyro_stop_envelope
build/host/tools/gyro_stop_envelope --scenarios scenarios --jobs "$jobs" \
  --markdown docs/stop-protection.md --csv docs/stop-protection.csv >/dev/null
echo "Measured on the component of commit $(git log -1 --format=%h -- component)$(git diff --quiet HEAD -- component || echo ', with local changes')." >> docs/stop-protection.md
echo "wrote docs/stop-protection.md, docs/stop-protection.csv"
