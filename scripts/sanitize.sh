#!/usr/bin/env bash
# Builds the host test suite and everything it runs under AddressSanitizer and
# UndefinedBehaviorSanitizer (preset host-asan: build/host-asan, RelWithDebInfo,
# -fno-sanitize-recover=all, GYRO_SUITE_ONLY: not the documentation tools nor the
# compile-only checks) and runs the whole suite with them; any sanitizer report fails its test.
# Usage: scripts/sanitize.sh [extra ctest arguments...]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset host-asan
cmake --build --preset host-asan
ctest --preset host-asan "$@"
