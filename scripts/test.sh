#!/usr/bin/env bash
# Builds everything for the host and runs the whole test suite, then the traceability check:
# scripts/trace.py reads the run's JUnit file (build/<preset>/junit.xml) and fails when a
# requirement of docs/requirements.md has no passing test, a test names an unknown requirement,
# a test of the flight code names none, or docs/traceability.md is not what the run generates.
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
/usr/bin/python3 scripts/trace.py --junit "build/$preset/junit.xml" --output "build/$preset/traceability.md" \
  --compare docs/traceability.md
