#!/usr/bin/env bash
# Builds everything for the host and runs the whole test suite, then the traceability check:
# scripts/trace.py reads the run's JUnit file (build/host/junit.xml) and fails when a
# requirement of docs/requirements.md has no passing test, a test names an unknown requirement,
# a test of the flight code names none, or docs/traceability.md is not what the run generates.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset host
cmake --build --preset host
ctest --preset host
/usr/bin/python3 scripts/trace.py --junit build/host/junit.xml --output build/host/traceability.md \
  --compare docs/traceability.md
