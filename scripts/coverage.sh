#!/usr/bin/env bash
# Line and branch coverage of the flight libraries (component/ and port/) by the host test
# suite: builds it with --coverage at -O0 in build/coverage, runs ctest, and has gcovr report
# on the two directories only (the header-only templates are attributed to their headers).
# Prints the summary and the uncovered lines, writes build/coverage/html/index.html, and
# fails if line coverage is below GYRO_COVERAGE_MIN_LINES (95 by default).
#
#   scripts/coverage.sh        # needs gcovr (apt-get install gcovr) and the test dependencies
set -euo pipefail
cd "$(dirname "$0")/.."
root="$(pwd)"
build="${GYRO_COVERAGE_BUILD_DIR:-build/coverage}"
min_lines="${GYRO_COVERAGE_MIN_LINES:-95}"
jobs="${GYRO_COVERAGE_JOBS:-2}"

command -v gcovr > /dev/null || {
  echo "coverage: needs gcovr (apt-get install gcovr)" >&2
  exit 2
}

# -O0: every line and branch of the source is in the object code; Debug keeps assertions.
# Warnings stay errors on our targets (gyro_warnings).
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Debug \
  -DCMAKE_CXX_FLAGS="--coverage -O0" \
  -DCMAKE_EXE_LINKER_FLAGS="--coverage" \
  -DGYRO_BUILD_TESTS=ON
cmake --build "$build" -j "$jobs"

# Counters of an earlier run would add up with this one.
find "$build" -name '*.gcda' -delete
# Left out, as they add nothing to the coverage of component/ and port/:
#   install_consumer             builds a separate project against the installed package,
#                                without instrumentation;
#   GyroModelOrthonormality.*    1e6- and 1e7-step soak runs of the step path that every
#                                other GyroModel test covers; instrumented at -O0 they take
#                                minutes, the 1e7-step one beyond ctest's 600 s limit.
ctest --test-dir "$build" -j "$jobs" --output-on-failure \
  -E '^(install_consumer|GyroModelOrthonormality\..*)$'

mkdir -p "$build/html"
# --exclude-throw-branches: the tests are built with exceptions (GoogleTest); the branches the
# compiler adds for unwinding through noexcept code are not the component's decisions.
# --exclude-unreachable-branches: compiler-generated branches on lines without code.
gcovr --root "$root" --object-directory "$build" \
  --filter "$root/component/" --filter "$root/port/" \
  --exclude-directories '.*/CMakeFiles/[0-9.]+/.*' \
  --exclude-throw-branches --exclude-unreachable-branches -j "$jobs" \
  --json "$build/coverage.json"
report=(--root "$root" --add-tracefile "$build/coverage.json")

echo "== lines: uncovered lines per file"
gcovr "${report[@]}" --txt --sort-uncovered
echo "== branches: per file"
gcovr "${report[@]}" --txt --branches --sort-uncovered
echo "== summary"
rc=0
gcovr "${report[@]}" --html-details "$build/html/index.html" --print-summary \
  --fail-under-line "$min_lines" > "$build/summary.txt" || rc=$?
cat "$build/summary.txt"
echo "HTML report: $build/html/index.html"
if [ "$rc" -ne 0 ]; then
  echo "coverage: line coverage below ${min_lines}% (gcovr exit $rc)"
  exit 1
fi
