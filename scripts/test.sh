#!/usr/bin/env bash
# Builds everything for the host and runs the whole test suite.
#   scripts/test.sh            the preset release (build/release): the flags of a plain Release
#                              build (-O3 -DNDEBUG), warnings as errors; what CI tests
#   scripts/test.sh host       the preset host (build/host, RelWithDebInfo: -O2 -g1, for
#                              backtraces and callgrind; the other scripts' build)
set -euo pipefail
cd "$(dirname "$0")/.."
preset=${1:-release}
scripts/setup.sh
cmake --preset "$preset"
cmake --build --preset "$preset"
ctest --preset "$preset"
