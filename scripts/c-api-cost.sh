#!/usr/bin/env bash
# The C API's cost per step against the C++ call (bench/c_api_ticks.cpp): instructions counted
# by callgrind over two run lengths, the difference per step, at -O2 on the x86-64 baseline
# (scripts/bench.sh's configuration, without the tools). Prints a Markdown table; docs/embedding.md
# quotes it.
#
#   scripts/c-api-cost.sh [BUILD_DIR]        (default build/bench-c-api)
# Needs: cmake, g++, Eigen, Google Benchmark and Boost headers (bench/), valgrind.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$root/build/bench-c-api}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O2 -DNDEBUG" \
  -DGYRO_BUILD_BENCH=ON -DGYRO_BUILD_TESTS=OFF -DGYRO_BUILD_TOOLS=OFF -DGYRO_BUILD_FORTRAN=OFF \
  -DGYRO_BUILD_OCTAVE=OFF >/dev/null
cmake --build "$build" -j2 --target gyro_bench_c_api >/dev/null

short=10000
long=20000
per_step() {  # per_step KIND: (instructions of LONG steps - of SHORT steps) / (LONG - SHORT)
  local n ir=()
  for n in $short $long; do
    valgrind --tool=callgrind --callgrind-out-file="$build/c-api.$1.$n.out" \
      "$build/bench/gyro_bench_c_api" "$1" "$n" 2>/dev/null
    ir+=("$(awk '/^totals:/ {print $2}' "$build/c-api.$1.$n.out")")
  done
  echo $(( (ir[1] - ir[0]) / (long - short) ))
}

echo "| step | C++ (inline) | C API (libgyro.so) | more |"
echo "|---|---:|---:|---:|"
for what in "advance double" "advance float" "model double" "model float"; do
  set -- $what
  cpp=$(per_step "$1_cpp_$2")
  c=$(per_step "$1_c_$2")
  label="exact step, one state ($2)"
  [ "$1" = model ] && label="GyroModel step ($2)"
  echo "| $label | $cpp | $c | $((c - cpp)) |"
done
echo "| exact step, a batch of 1000 states (double), per state | | $(per_step batch_c_double) | |"
