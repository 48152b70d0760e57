#!/usr/bin/env bash
# Instructions per tick of the flight component (GyroComponent::step), for docs/performance.md:
#   1. x86-64 -O2, the case of bench/component_tick_case.hpp (the seeker example slewing on a
#      turning body; spin readback steady, then changing every tick), double and float:
#      callgrind around each step, the difference of a 2,000- and a 4,000-tick run;
#   2. x86-64 -O2, every scenario in scenarios/, double and float, each step counted on its
#      own (callgrind dumps after every GyroComponent::step): min, median, max per scenario
#      and per mode, with the mode and flags of the largest tick;
#   3. Cortex-M4F (float, mps2-an386) and Cortex-M7 (double, mps2-an500): gyro_fw_tick_cost
#      under qemu-system-arm -icount shift=0, every step of the case of 1. counted exactly
#      (firmware/tick_cost/component_tick_cost.cpp: 40 phase-shifted runs against SysTick).
# Writes RESULTS/component_tick.csv, worst_tick.csv, target_<preset>.txt and prints the tables
# (bench/tick_cost_report.py). scripts/bench.sh runs it and puts the tables in the docs.
#
#   scripts/tick-cost.sh [BUILD_DIR [RESULTS]]   (default build-bench, BUILD_DIR/bench-results/tick-cost)
#
# Needs: cmake, g++, valgrind (and its headers), nlohmann-json, CLI11, gcc-arm-none-eabi,
# libnewlib-arm-none-eabi, libstdc++-arm-none-eabi-newlib, qemu-system-arm, python3.
# About 5 minutes on two cores from a built tree (the x86-64 build of gyro_sil: 3 more).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$root/build-bench}
results=${2:-$build/bench-results/tick-cost}
say() { printf '== %s\n' "$*" >&2; }
for tool in cmake valgrind python3 qemu-system-arm arm-none-eabi-g++ nm; do
  command -v "$tool" >/dev/null || { echo "tick-cost.sh: $tool is missing" >&2; exit 1; }
done
rm -rf "$results"
mkdir -p "$results/callgrind"

say "x86-64: configure and build gyro_sil, gyro_bench_component_tick ($build, -O2)"
# The same configuration as scripts/bench.sh: -O2 everywhere, the tools built for gyro_sil.
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O2 -DNDEBUG" \
  -DGYRO_BUILD_BENCH=ON -DGYRO_BUILD_TESTS=OFF -DGYRO_BUILD_TOOLS=ON >/dev/null
cmake --build "$build" -j2 --target gyro_sil gyro_bench_component_tick >/dev/null
sil=$build/apps/gyro_sil

# Instructions collected by callgrind in one run: "$@" is the command.
collected() {
  local out=$1
  shift
  valgrind --tool=callgrind --callgrind-out-file="$out" "$@" >/dev/null 2>>"$results/valgrind.log"
  awk '/^totals:/ {print $2}' "$out"
}

say "x86-64: the component's tick on the bench case (2,000 and 4,000 ticks)"
echo "type,case,ticks,instructions" > "$results/component_tick.csv"
for type in double float; do
  for which in steady spin_down; do
    for n in 2000 4000; do
      ir=$(collected "$results/callgrind/tick.$type.$which.$n.out" --collect-atstart=no \
        "$build/bench/gyro_bench_component_tick" "$type" "$which" "$n")
      echo "$type,$which,$n,$ir" >> "$results/component_tick.csv"
    done
  done
done

say "x86-64: every step of every scenario counted on its own"
echo "scenario,type,tick,instructions,mode,flags,request,active_faults,step_status" > "$results/worst_tick.csv"
for scenario in "$root"/scenarios/*.json; do
  name=$(basename "$scenario" .json)
  for type in double float; do
    # callgrind matches --dump-after by the exact demangled name.
    step=$(nm -C "$sil" | sed -n "s/^[0-9a-f]* [TW] \(gyro::GyroComponent<$type>::step(.*)\)$/\1/p" | head -n1)
    [ -n "$step" ] || { echo "tick-cost.sh: no GyroComponent<$type>::step in $sil" >&2; exit 1; }
    out=$results/callgrind/sil.$name.$type.out
    valgrind --tool=callgrind --callgrind-out-file="$out" --dump-line=no --combine-dumps=yes \
      --toggle-collect="$step" --dump-after="$step" \
      "$sil" "$scenario" --precision "$type" -q -o "$results/sil.csv" >/dev/null 2>>"$results/valgrind.log"
    python3 "$root/bench/tick_cost_report.py" --join "$name" "$type" "$out" "$results/sil.csv" \
      >> "$results/worst_tick.csv"
    rm -f "$out" "$results/sil.csv"
  done
done

for preset in cortex-m4f cortex-m7; do
  case $preset in cortex-m4f) machine=mps2-an386 ;; cortex-m7) machine=mps2-an500 ;; esac
  say "$preset: build gyro_fw_tick_cost and run it under qemu-system-arm -M $machine -icount shift=0"
  tbuild=$build/$preset
  cmake -S "$root" -B "$tbuild" -DCMAKE_TOOLCHAIN_FILE="$root/toolchains/arm-none-eabi-$preset.cmake" \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
  cmake --build "$tbuild" -j2 --target gyro_fw_tick_cost >/dev/null
  qemu-system-arm -M "$machine" -icount shift=0 -nographic -monitor none -serial none \
    -semihosting-config enable=on,target=native -kernel "$tbuild/firmware/gyro_fw_tick_cost.elf" \
    > "$results/target_$preset.txt" 2>&1  # semihosting writes to standard error
done

python3 "$root/bench/tick_cost_report.py" --tables "$results"
say "done: $results"
