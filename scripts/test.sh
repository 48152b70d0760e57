#!/usr/bin/env bash
# Builds everything for the host and runs the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset host
cmake --build --preset host
ctest --preset host
