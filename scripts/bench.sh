#!/usr/bin/env bash
# Benchmarks of the exact rotor propagator against the integrators a user would pick instead.
# One command: builds (Release = -O2, x86-64 baseline), finds each contender's steps for the
# accuracy target, counts instructions with callgrind (also of the SIL stub's gimbal plant), times
# with Google Benchmark, counts the flight component's tick on x86-64, over every scenario and on
# the Cortex-M4F/M7 under QEMU (scripts/tick-cost.sh), and writes docs/performance.md with
# docs/img/*.png.
#
#   scripts/bench.sh [BUILD_DIR]        (default build-bench; raw results in BUILD_DIR/bench-results)
#
# Needs: cmake, g++, Eigen, Google Benchmark (libbenchmark-dev), Boost headers (libboost-dev),
# valgrind, gnuplot (gnuplot-nox), python3, objdump, and for scripts/tick-cost.sh nlohmann-json,
# CLI11, gcc-arm-none-eabi (with newlib), qemu-system-arm. About 12 minutes on two cores.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$root/build-bench}
results=$build/bench-results
bin=$build/bench
# Euler and AB2 need millions of steps: their instructions are counted on this many steps
# (at their real step size) and scaled; the wall-time program does the same on 2^20 steps.
counted_steps=262144
reps=7

say() { printf '== %s\n' "$*" >&2; }
for tool in cmake valgrind gnuplot python3 objdump; do
  command -v "$tool" >/dev/null || { echo "bench.sh: $tool is missing" >&2; exit 1; }
done

say "configure and build ($build)"
# -O2 everywhere and the tools on: the configuration scripts/tick-cost.sh uses (gyro_sil).
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O2 -DNDEBUG" \
  -DGYRO_BUILD_BENCH=ON -DGYRO_BUILD_TESTS=OFF -DGYRO_BUILD_TOOLS=ON >/dev/null
cmake --build "$build" -j2 --target gyro_bench_calibrate gyro_bench_driver gyro_bench_wall \
  gyro_bench_latency gyro_bench_gimbal_integrators >/dev/null

rm -rf "$results"
mkdir -p "$results/callgrind" "$results/samples"
{
  echo "date: $(date -u +%Y-%m-%dT%H:%MZ)"
  echo "commit: $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
  echo "uncommitted changes under component/: $(git -C "$root" status --porcelain -- component 2>/dev/null | wc -l) files"
  echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
  echo "cores: $(nproc)"
  echo "compiler: $(${CXX:-c++} --version | head -n1)"
  echo "flags: $(grep -m1 '^CMAKE_CXX_FLAGS:' "$build/CMakeCache.txt" | cut -d= -f2-) -O2 -DNDEBUG"
  echo "valgrind: $(valgrind --version)"
  echo "benchmark: $(dpkg-query -W -f='${Version}' libbenchmark-dev 2>/dev/null || echo unknown)"
  echo "boost: $(dpkg-query -W -f='${Version}' libboost-dev 2>/dev/null || echo unknown)"
} > "$results/env.txt"

say "accuracy calibration (steps and tolerances for a worst angle error < 1e-6 rad)"
"$bin/gyro_bench_calibrate" "$results" 2> "$results/calibrate.log"

# Instructions of the functions gyro_bench_measured_* only (setup is not counted).
count() {
  local name=$1
  shift
  valgrind --tool=callgrind --callgrind-out-file="$results/callgrind/$name.out" \
    --toggle-collect='gyro_bench_measured_*' "$@" >/dev/null 2>>"$results/valgrind.log"
  awk '/^totals:/ {print $2}' "$results/callgrind/$name.out"
}

# Instructions per simulated second of every row of DIR/calibration.csv -> DIR/instructions.csv
count_seconds() {
  local dir=$1 tag=$2
  echo "case,contender,steps,counted_steps,instructions" > "$dir/instructions.csv"
  tail -n +2 "$dir/calibration.csv" | while IFS=, read -r case_id who steps tol _; do
    local run=$steps ir
    case $who in
      dopri5) ir=$(count "$tag$case_id.$who" "$bin/gyro_bench_driver" second "$case_id" "$who" "$steps" "$tol") ;;
      euler|ab2) run=$(( steps < counted_steps ? steps : counted_steps ))
              ir=$(count "$tag$case_id.$who" "$bin/gyro_bench_driver" second "$case_id" "$who" "$steps" "$run") ;;
      *) ir=$(count "$tag$case_id.$who" "$bin/gyro_bench_driver" second "$case_id" "$who" "$steps") ;;
    esac
    echo "$case_id,$who,$steps,$run,$ir" >> "$dir/instructions.csv"
  done
}

say "instructions per simulated second (callgrind)"
count_seconds "$results" ""

say "sensitivity: accuracy target 1e-9 rad at the report's gyro and at 5 kHz nutation"
mkdir -p "$results/target_1e-9"
"$bin/gyro_bench_calibrate" --target=1e-9 --skip=euler "$results/target_1e-9" report sweep_05000 \
  2> "$results/target_1e-9/calibrate.log"
count_seconds "$results/target_1e-9" "t9."

say "check of the scaling: AB2 at 5 kHz nutation, all of its steps"
ab2_steps=$(awk -F, '$1=="sweep_05000" && $2=="ab2" {print $3}' "$results/calibration.csv")
ir=$(count sweep_05000.ab2.full "$bin/gyro_bench_driver" second sweep_05000 ab2 "$ab2_steps")
echo "case,contender,steps,instructions" > "$results/scaling_check.csv"
echo "sweep_05000,ab2,$ab2_steps,$ir" >> "$results/scaling_check.csv"

say "instructions per tick (callgrind; two run lengths, the difference is the per-tick cost)"
echo "kind,ticks,instructions" > "$results/ticks.csv"
kinds="advance_double advance_float advance_unchecked_double advance_lean_double advance_lean_float
       propagate_double propagate_double_100hz make_transition_double make_transition_double_100hz"
if [ -f "$root/component/report/include/gyro/gyro_model.hpp" ]; then kinds="$kinds model_double model_float"; fi
for kind in $kinds; do
  for n in 10000 20000; do
    ir=$(count "tick.$kind.$n" "$bin/gyro_bench_driver" ticks "$kind" "$n")
    echo "$kind,$n,$ir" >> "$results/ticks.csv"
  done
done

if [ -f "$root/component/report/include/gyro/gyro_model.hpp" ]; then
  say "component full tick: every 4999th of 1e6 ticks counted on its own"
  echo "type,sample,instructions" > "$results/model_samples.csv"
  for type in double float; do
    rm -f "$results/samples/"*
    valgrind --tool=callgrind --instr-atstart=no --collect-atstart=no \
      --callgrind-out-file="$results/samples/s" \
      "$bin/gyro_bench_driver" model_sample "$type" 1000000 4999 >/dev/null 2>>"$results/valgrind.log"
    for f in "$results/samples/s."*; do
      printf '%s,%s,%s\n' "$type" "${f##*.}" "$(awk '/^totals:/ {print $2}' "$f")"
    done | sort -t, -k2,2n >> "$results/model_samples.csv"
  done
  rm -rf "$results/samples"
fi

say "gimbal plant of the SIL stub: instructions per tick (two run lengths)"
echo "kind,type,ticks,instructions,substeps,tick_s" > "$results/gimbal.csv"
for run in "seeker double" "seeker float" "seeker_coarse double" "report double" "report float"; do
  set -- $run
  for n in 2000 4000; do
    out=$(valgrind --tool=callgrind --callgrind-out-file="$results/callgrind/gimbal.$1.$2.$n.out" \
      --toggle-collect='gyro_bench_measured_*' "$bin/gyro_bench_driver" gimbal "$1" "$2" "$n" 2>>"$results/valgrind.log")
    ir=$(awk '/^totals:/ {print $2}' "$results/callgrind/gimbal.$1.$2.$n.out")
    shape=$(sed -n 's/.*substeps \([0-9]*\) tick \([0-9.e+-]*\) s.*/\1,\2/p' <<< "$out")
    echo "$1,$2,$n,$ir,$shape" >> "$results/gimbal.csv"
  done
done

say "gimbal plant against Odeint on its right-hand side, at equal error (1e-7 rad over 1 s)"
"$bin/gyro_bench_gimbal_integrators" calibrate 1e-7 > "$results/gimbal_integrators.calibration.csv"
echo "case,contender,setting,error_rad,evaluations,instructions" > "$results/gimbal_integrators.csv"
tail -n +2 "$results/gimbal_integrators.calibration.csv" | while IFS=, read -r case_id who setting err evals; do
  ir=$(count "gi.$case_id.$who" "$bin/gyro_bench_gimbal_integrators" run "$case_id" "$who" "$setting")
  echo "$case_id,$who,$setting,$err,$evals,$ir" >> "$results/gimbal_integrators.csv"
done

say "one run of campaigns/seeker_faults.json (scripts/campaign-run-cost.sh)"
cmake --build "$build" -j2 --target gyro_campaign >/dev/null
"$root/scripts/campaign-run-cost.sh" "$build" "$results/campaign_run.csv" >/dev/null

say "the flight component's tick: x86-64, every scenario, Cortex-M4F/M7 (scripts/tick-cost.sh)"
"$root/scripts/tick-cost.sh" "$build" "$results/tick-cost" > "$results/tick-cost.txt"

say "wall time (Google Benchmark, median of $reps repetitions)"
"$bin/gyro_bench_wall" --calibration="$results/calibration.csv" \
  --benchmark_repetitions=$reps --benchmark_report_aggregates_only=true \
  --benchmark_min_time=0.05 --benchmark_out="$results/wall.json" \
  --benchmark_out_format=json > "$results/wall.txt" 2>&1

say "per-tick time over 1e6 consecutive ticks"
"$bin/gyro_bench_latency" 1000000 > "$results/latency.csv"

say "disassembly of the exact step"
objdump -d --no-show-raw-insn -C "$bin/gyro_bench_driver" > "$results/driver.asm"

say "report: docs/performance.md, docs/img/*.png"
python3 "$root/bench/make_report.py" "$results" "$root/docs"
say "done"
