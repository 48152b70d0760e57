#!/usr/bin/env bash
# Soak: 1e8 ticks (1,000 flights of 1e5 ticks) of the component against the stub.
# Usage: scripts/soak.sh [ticks]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset host >/dev/null
cmake --build --preset host --target gyro_soak
build/host/tools/gyro_soak scenarios/seeker_slew.json "${1:-100000000}"
