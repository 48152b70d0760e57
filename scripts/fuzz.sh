#!/usr/bin/env bash
# Builds the libFuzzer targets (preset "fuzz": clang++, ASan + UBSan; build/fuzz) and runs
# each for a bounded time from the committed corpus and regression inputs (fuzz/README.md).
#
# Usage: scripts/fuzz.sh [seconds per target (default 60)] [target ...]
#
# New corpus entries go to build/fuzz/corpus/<target>/ (scratch, not committed; kept between
# runs). A crash or broken invariant is saved as build/fuzz/artifacts/<target>/crash-* and
# fails the script once every target has run; replay it with
#   build/fuzz/fuzz/<target> <file>
# and, once fixed, commit it to fuzz/regressions/<target>/ (the host ctest replays it).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(fuzz_rotor_step fuzz_component_tick fuzz_frame_decoder fuzz_scenario_parser
                                    fuzz_campaign_file)
case "$seconds" in '' | *[!0-9]*) echo "usage: $0 [seconds] [target ...]" >&2; exit 2 ;; esac

scripts/setup.sh clang libclang-rt-14-dev
cmake --preset fuzz
cmake --build --preset fuzz

declare -A max_len=([fuzz_rotor_step]=512 [fuzz_component_tick]=4096 [fuzz_frame_decoder]=2048
                   [fuzz_scenario_parser]=8192 [fuzz_campaign_file]=16384)
summary=()
failed=()
for t in "${targets[@]}"; do
  exe=build/fuzz/fuzz/$t
  work=build/fuzz/corpus/$t
  artifacts=build/fuzz/artifacts/$t
  log=build/fuzz/logs/$t.log
  mkdir -p "$work" "$artifacts" "$(dirname "$log")"
  dirs=("$work" "fuzz/corpus/$t")
  [ -d "fuzz/regressions/$t" ] && dirs+=("fuzz/regressions/$t")
  opts=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len="${max_len[$t]:-4096}"
        -print_final_stats=1 -artifact_prefix="$artifacts/")
  [ -f "fuzz/$t.dict" ] && opts+=(-dict="fuzz/$t.dict")
  echo "== $t: ${seconds} s (${dirs[*]})"
  set +e
  timeout --signal=INT $((seconds + 300)) "$exe" "${opts[@]}" "${dirs[@]}" > "$log" 2>&1
  rc=$?
  set -e
  # The last status line has the coverage; the final stats the executions and their rate.
  status=$(grep -E '^#[0-9]+[[:space:]]+(DONE|pulse|NEW|REDUCE|INITED)' "$log" | tail -n 1 || true)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<< "$status")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<< "$status")
  corp=$(sed -n 's/.* corp: \([^ ]*\).*/\1/p' <<< "$status")
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -n 1)
  took=$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$log" | tail -n 1)
  result=ok
  if [ "$rc" -ne 0 ]; then
    result="FAILED (exit $rc)"
    failed+=("$t")
    grep -E 'invariant violated|ERROR: |runtime error|SUMMARY|Test unit written' "$log" | head -n 8 || true
  fi
  line=$(printf '%-22s runs %-10s exec/s %-7s cov %-6s ft %-6s corpus %-12s time %ss  %s' \
         "$t" "${runs:-?}" "${rate:-?}" "${cov:-?}" "${ft:-?}" "${corp:-?}" "${took:-?}" "$result")
  echo "$line"
  summary+=("$line")
done

echo
echo "fuzzing summary (${seconds} s per target; logs in build/fuzz/logs/):"
printf '  %s\n' "${summary[@]}"
if [ ${#failed[@]} -gt 0 ]; then
  echo "crashes in: ${failed[*]} (inputs in build/fuzz/artifacts/)" >&2
  exit 1
fi
