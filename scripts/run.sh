#!/usr/bin/env bash
# Builds the host tools and runs the report's sample run; the time history goes to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset host
cmake --build --preset host --target gyro_report_sample
mkdir -p out
build/host/apps/gyro_report_sample out/report_sample.csv
echo "time history: out/report_sample.csv"
