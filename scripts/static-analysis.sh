#!/usr/bin/env bash
# Static analysis of the flight libraries (component/, port/, hil_stub/): clang-tidy with the
# check set of .clang-tidy and cppcheck (warning, performance, portability, style). Exits
# non-zero on any finding. docs/coding-rules.md lists the checks and every exclusion.
#
# Both tools analyse tests/flight_rules_check.cpp, the translation unit that includes every
# public header by name and instantiates every template for float and double (uninstantiated
# template code is invisible to most checks). This script first checks that no header is
# missing from it. Eigen is a system header: clang-tidy sees it through -isystem (from the
# compile_commands.json of a host configure) and reports nothing in it; cppcheck is not given
# Eigen's include path at all.
#
#   scripts/static-analysis.sh            # needs clang-tidy (14) and cppcheck (2.10)
#   GYRO_SA_BUILD_DIR=dir scripts/static-analysis.sh
set -euo pipefail
cd "$(dirname "$0")/.."

build_dir="${GYRO_SA_BUILD_DIR:-build/static-analysis}"
tu=tests/flight_rules_check.cpp
clang_tidy="${CLANG_TIDY:-$(command -v clang-tidy-14 || command -v clang-tidy || true)}"
cppcheck="${CPPCHECK:-$(command -v cppcheck || true)}"
if [ -z "$clang_tidy" ] || [ -z "$cppcheck" ]; then
  echo "static-analysis: needs clang-tidy and cppcheck (apt-get install clang-tidy cppcheck)" >&2
  exit 2
fi

failed=0

# 1. Every header of the three libraries is in the analysed translation unit.
echo "== headers in $tu"
for h in component/include/gyro/*.hpp port/include/gyro/*.hpp hil_stub/include/gyro/*.hpp; do
  name="gyro/$(basename "$h")"
  if ! grep -q "^#include \"${name}\"" "$tu"; then
    echo "$tu: does not include \"$name\": the header would escape the analysis"
    failed=1
  fi
done

# 2. compile_commands.json of a host configure (nothing is built).
echo "== configure $build_dir (compile_commands.json)"
mkdir -p "$build_dir"
cmake -S . -B "$build_dir" -DCMAKE_EXPORT_COMPILE_COMMANDS=ON -DGYRO_BUILD_TOOLS=OFF \
  -DGYRO_BUILD_TESTS=ON -DCMAKE_BUILD_TYPE=Debug > "$build_dir/configure.log" 2>&1 || {
  cat "$build_dir/configure.log"
  exit 2
}

# 3. clang-tidy: the checks, header filter and warnings-as-errors come from .clang-tidy.
echo "== $("$clang_tidy" --version | grep -m1 -o 'LLVM version [0-9.]*' | sed 's/LLVM/clang-tidy (LLVM)/')"
tidy_log="$build_dir/clang-tidy.log"
tidy_rc=0
"$clang_tidy" -p "$build_dir" --quiet "$tu" > "$tidy_log" 2>&1 || tidy_rc=$?
if [ "$tidy_rc" -ne 0 ] || grep -qE '(warning|error):' "$tidy_log"; then
  grep -vE '^[0-9]+ warnings? (and [0-9]+ errors? )?generated\.$' "$tidy_log" || true
  echo "clang-tidy: FINDINGS (exit $tidy_rc)"
  failed=1
else
  echo "clang-tidy: clean"
fi

# 4. cppcheck on the same translation unit, our include directories only.
echo "== $("$cppcheck" --version)"
cppcheck_log="$build_dir/cppcheck.log"
cppcheck_rc=0
"$cppcheck" --enable=warning,performance,portability,style --inline-suppr --std=c++17 \
  --language=c++ --error-exitcode=1 --quiet \
  -I component/include -I port/include -I hil_stub/include \
  --suppress=missingIncludeSystem \
  --template='{file}:{line}:{column}: {severity}: {message} [{id}]' \
  "$tu" > "$cppcheck_log" 2>&1 || cppcheck_rc=$?
if [ "$cppcheck_rc" -ne 0 ] || [ -s "$cppcheck_log" ]; then
  cat "$cppcheck_log"
  echo "cppcheck: FINDINGS (exit $cppcheck_rc)"
  failed=1
else
  echo "cppcheck: clean"
fi

if [ "$failed" -ne 0 ]; then
  echo "static-analysis: FAILED"
  exit 1
fi
echo "static-analysis: clean (clang-tidy, cppcheck) on component/, port/, hil_stub/"
