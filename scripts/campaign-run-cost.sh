#!/usr/bin/env bash
# Instructions of a run of campaigns/seeker_faults.json (callgrind): its first shard of 100 (21
# runs, every fault kind and the fault-free) with gyro_campaign, per run on average, split into
# the run (execute_run), the gimbal plant, the flight component, the run's own set-up and
# bookkeeping (the run less its SIL loop's ticks); and the process's start-up, once per
# campaign. scripts/bench.sh calls it; docs/performance.md shows the result.
#
#   scripts/campaign-run-cost.sh BUILD_DIR OUT.csv     (BUILD_DIR has gyro_campaign built)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=$1
out=$2
exe=$build/apps/campaign/gyro_campaign
[ -x "$exe" ] || { echo "campaign-run-cost.sh: $exe is missing" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
valgrind --tool=callgrind --callgrind-out-file="$work/cg.out" "$exe" run "$root/campaigns/seeker_faults.json" \
  --shard 1/100 -o "$work/out" --no-plots --quiet >/dev/null 2>"$work/valgrind.log"
runs=$(($(wc -l < "$work/out/runs.csv") - 1))
callgrind_annotate --inclusive=yes "$work/cg.out" > "$work/annotate.txt" 2>/dev/null
# The inclusive count of the first line naming $1 (not one of its lambdas).
inclusive() {
  grep -F "$1" "$work/annotate.txt" | grep -v -F '::{lambda' | head -n1 | awk '{gsub(",", "", $1); print $1}'
}
total=$(awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1; exit}' "$work/annotate.txt")
run=$(inclusive 'gyro::campaign::execute_run(')
plant=$(inclusive 'gyro::GimbalPlant<double>::step(')
component=$(inclusive 'gyro::GyroComponent<double>::step(')
ticks=$(inclusive 'gyro::SilLoop<double, gyro::sil::FlightComputer<double> >::tick(')
for v in "$total" "$run" "$plant" "$component" "$ticks"; do
  [ -n "$v" ] || { echo "campaign-run-cost.sh: a function was not found in the profile" >&2; exit 1; }
done
{
  echo "part,instructions"
  echo "runs,$runs"
  echo "startup,$((total - run))"
  echo "run,$((run / runs))"
  echo "plant,$((plant / runs))"
  echo "component,$((component / runs))"
  echo "ticks,$((ticks / runs))"
  echo "overhead,$(((run - ticks) / runs))"
} > "$out"
cat "$out"
