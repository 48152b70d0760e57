#!/usr/bin/env bash
# Builds the host tools and runs the report's sample through the flight component and the
# simulated gyro (gyro_sil): the time history (CSV) and the plot of the gimbal angles go to
# out/. Then the report's GYRO model alone (gyro_report_sample) prints the sample's figures.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset host
cmake --build --preset host --target gyro_sil gyro_report_sample
mkdir -p out
build/host/apps/gyro_sil scenarios/report_sample.json -o out/report_sample.csv --plot out/report_sample.png
build/host/apps/gyro_report_sample out/report_sample_model.csv
echo "time history: out/report_sample.csv (component + simulated gyro), out/report_sample_model.csv (model alone)"
echo "plot:         out/report_sample.png"
