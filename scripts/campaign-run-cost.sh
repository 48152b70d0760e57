#!/usr/bin/env bash
# Instructions of one run of campaigns/seeker_faults.json (callgrind): a one-run campaign (its
# run 0) with gyro_campaign, split into the run (execute_run), the gimbal plant, the flight
# component, the run's own set-up and bookkeeping (the run less its SIL loop's ticks) and the
# process's start-up. scripts/bench.sh calls it; docs/performance.md shows the result.
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
python3 - "$root/campaigns/seeker_faults.json" "$work/one.json" <<'PY'
import json, os, sys
src, dst = sys.argv[1], sys.argv[2]
d = json.load(open(src))
d["runs"] = 1
d["base"] = os.path.normpath(os.path.join(os.path.dirname(src), d["base"]))
json.dump(d, open(dst, "w"), indent=1)
PY
valgrind --tool=callgrind --callgrind-out-file="$work/cg.out" "$exe" run "$work/one.json" -o "$work/out" \
  --no-plots --quiet >/dev/null 2>"$work/valgrind.log"
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
  echo "total,$total"
  echo "run,$run"
  echo "plant,$plant"
  echo "component,$component"
  echo "ticks,$ticks"
  echo "overhead,$((run - ticks))"
} > "$out"
cat "$out"
