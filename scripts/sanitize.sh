#!/usr/bin/env bash
# Builds everything for the host under AddressSanitizer and UndefinedBehaviorSanitizer
# (preset host-asan: build/host-asan, RelWithDebInfo, -fno-sanitize-recover=all) and runs the
# whole test suite with them; any sanitizer report fails its test.
# Usage: scripts/sanitize.sh [extra ctest arguments...]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset host-asan
cmake --build --preset host-asan
ctest --preset host-asan "$@"
