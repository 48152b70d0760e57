#!/usr/bin/env bash
# Static analysis of the flight libraries (component/, port/, hil_stub/, pil/): clang-tidy with the
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

# 1. Every header of the libraries (subfolders included: gyro/link/...) is in the analysed
# translation unit.
mapfile -t lib_headers < <(find component/*/include/gyro port/include/gyro hil_stub/include/gyro examples/include/gyro pil/include/gyro \
  -name '*.hpp' | sort)
echo "== headers in $tu"
for h in "${lib_headers[@]}"; do
  name="${h#*/include/}"
  if ! grep -q "^#include \"${name}\"" "$tu"; then
    echo "$tu: does not include \"$name\": the header would escape the analysis"
    failed=1
  fi
done

# 2. Constructs the flight rules ban from the three libraries (docs/coding-rules.md), looked
# for in the code with // comments removed. The compiler flags and the tests enforce most of
# these too; this names the rule and the line.
echo "== banned constructs in component/, port/, hil_stub/, pil/"
ban() {  # ban <rule> <extended regex> [<regex of allowed matches>]
  local rule="$1" re="$2" allow="${3:-}" h hits
  for h in "${lib_headers[@]}"; do
    hits="$(sed 's://.*$::' "$h" | grep -nE "$re" || true)"
    if [ -n "$allow" ] && [ -n "$hits" ]; then hits="$(grep -vE "$allow" <<< "$hits" || true)"; fi
    if [ -n "$hits" ]; then
      sed "s|^|$h:|; s|\$| [$rule]|" <<< "$hits"
      failed=1
    fi
  done
}
ban no-heap '\bnew\b|\bdelete\b|\b(malloc|calloc|realloc|free|aligned_alloc)[[:space:]]*\(' \
  '=[[:space:]]*delete\b'
ban no-heap 'std::(vector|string|basic_string|list|deque|map|set|multimap|multiset|unordered_[a-z]+|function|unique_ptr|shared_ptr|make_unique|make_shared|allocator)\b'
ban no-heap '#include[[:space:]]*<(vector|string|list|deque|map|set|unordered_map|unordered_set|memory|functional|iostream|sstream|fstream|regex)>'
ban no-exceptions-no-rtti '\b(throw|try|catch|typeid|dynamic_cast)\b'
ban no-clock-reads '#include[[:space:]]*<(chrono|ctime|time\.h|sys/time\.h|random|thread|mutex)>'
ban no-clock-reads 'std::chrono|\b(clock_gettime|gettimeofday|random_device|rand|srand)\b|\b(time|clock)[[:space:]]*\('
ban fixed-size-eigen-only '\bDynamic\b|\b(Matrix|Vector|RowVector|Array)X'
ban bounded-loops '\b(while|goto)\b|\bdo[[:space:]]*\{'
# Every function returning a status is [[nodiscard]] (declared on the line of its return type).
ban nodiscard-status '^[[:space:]]*((static|virtual|inline|constexpr|friend)[[:space:]]+)*(Status|PortStatus|ConfigCheck|SampleRunSummary)[[:space:]]+[A-Za-z_][A-Za-z0-9_]*[[:space:]]*\('

# 3. compile_commands.json of a host configure (nothing is built).
echo "== configure $build_dir (compile_commands.json)"
mkdir -p "$build_dir"
cmake -S . -B "$build_dir" -DCMAKE_EXPORT_COMPILE_COMMANDS=ON -DGYRO_BUILD_TOOLS=OFF \
  -DGYRO_BUILD_TESTS=ON -DGYRO_BUILD_FORTRAN=OFF -DGYRO_BUILD_OCTAVE=OFF -DCMAKE_BUILD_TYPE=Debug \
  > "$build_dir/configure.log" 2>&1 || {
  cat "$build_dir/configure.log"
  exit 2
}

# 4. clang-tidy: the checks, header filter and warnings-as-errors come from .clang-tidy.
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

# 5. cppcheck on the same translation unit, our include directories only.
echo "== $("$cppcheck" --version)"
cppcheck_log="$build_dir/cppcheck.log"
cppcheck_rc=0
"$cppcheck" --enable=warning,performance,portability,style --inline-suppr --std=c++17 \
  --language=c++ --error-exitcode=1 --quiet \
  -I component/exact/include -I component/report/include -I component/flight/include -I port/include \
  -I hil_stub/include -I examples/include -I pil/include \
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
echo "static-analysis: clean (clang-tidy, cppcheck) on component/, port/, hil_stub/, pil/"
