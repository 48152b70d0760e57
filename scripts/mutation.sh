#!/usr/bin/env bash
# Mutation testing of the flight code: does the host test suite notice when one line of
# component/ changes? Each mutant of the list (scripts/mutants.tsv: file, exact text,
# replacement, meaning) is applied alone to a copy of the tree, the test targets are rebuilt
# incrementally, and the mutant is killed (a test failed or timed out), survived (every test
# passed) or build-failed. The GoogleTest executables are built (as many at once as jobs)
# and run first, the one that killed the last mutant first, and the first failure kills the
# mutant: most mutants cost one test executable's build, not the suite's. A mutant they all
# pass gets the whole build and ctest before it is called survived. A mutant judged on the
# same tree (the copied sources hashed) is not run again: an interrupted run resumes where it
# stopped. Prints a Markdown table and the score, killed over the non-equivalent mutants that
# built. Your checkout is never modified: the copy lives in the scratch directory
# (build/mutation by default), kept between runs so that they are incremental. On demand
# only (not in CI).
#
#   scripts/mutation.sh                        # every mutant, the whole host suite (hours)
#   scripts/mutation.sh -R '^Component' -m '^tick-'   # the tick mutants, Component* tests
#   scripts/mutation.sh -c                     # only check that every mutant's text is found once
#
# Options:
#   -R REGEX   run only the tests ctest -R selects (the targets built are then only theirs)
#   -E REGEX   leave out the tests ctest -E selects
#   -m REGEX   only the mutants whose id matches (grep -E)
#   -f FILE    the mutant list (default scripts/mutants.tsv)
#   -d DIR     scratch directory (default build/mutation; holds src/, build/, logs/)
#   -t TARGETS comma-separated targets to build (default: those of the selected tests)
#   -j N       build and test jobs (default 2)
#   -T SECONDS time limit of one ctest run (default 5 x the baseline's, at least 60 s)
#   -e         also run the mutants marked equivalent (reported, never scored)
#   -o FILE    write the Markdown report to FILE as well
#   -c         check the list against the checkout (each text found exactly once) and stop
#   -F         forget the verdicts recorded for this tree and judge every mutant again
# Exit status: 0 when every scored mutant was killed, 1 when one survived, failed to build or
# was refused, 2 on a usage error or a failing baseline.
set -euo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
list="$root/scripts/mutants.tsv"
scratch="$root/build/mutation"
test_regex=""
exclude_regex=""
mutant_regex=""
targets_opt=""
jobs=2
limit=""
run_equivalent=0
report_file=""
check_only=0
forget=0
python="$(command -v /usr/bin/python3 || command -v python3)"

usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'; }
while getopts "R:E:m:f:d:t:j:T:eo:cFh" opt; do
  case "$opt" in
    R) test_regex="$OPTARG" ;;
    E) exclude_regex="$OPTARG" ;;
    m) mutant_regex="$OPTARG" ;;
    f) list="$(cd "$(dirname "$OPTARG")" && pwd)/$(basename "$OPTARG")" ;;
    d) scratch="$OPTARG" ;;
    t) targets_opt="$OPTARG" ;;
    j) jobs="$OPTARG" ;;
    T) limit="$OPTARG" ;;
    e) run_equivalent=1 ;;
    o) report_file="$OPTARG" ;;
    c) check_only=1 ;;
    F) forget=1 ;;
    h) usage; exit 0 ;;
    *) usage >&2; exit 2 ;;
  esac
done
[[ -f "$list" ]] || { echo "mutation: no mutant list $list" >&2; exit 2; }
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || { echo "mutation: -j needs a positive count" >&2; exit 2; }
[[ -z "$limit" || "$limit" =~ ^[1-9][0-9]*$ ]] || { echo "mutation: -T needs seconds" >&2; exit 2; }
mkdir -p "$scratch"
scratch="$(cd "$scratch" && pwd)"
case "$scratch/" in
  "$root/build/"*) ;;  # inside the checkout's build area: fine
  "$root/"*) echo "mutation: the scratch directory must not be inside the sources (use build/...)" >&2; exit 2 ;;
esac
src="$scratch/src"
bld="$scratch/build"
logs="$scratch/logs"

# How often `text` occurs in `file`; with a replacement, writes the mutant when it is exactly once.
occurrences() {  # file text
  "$python" - "$1" "$2" <<'EOF'
import sys
print(open(sys.argv[1], encoding="utf-8").read().count(sys.argv[2]))
EOF
}
apply_mutant() {  # file text replacement
  "$python" - "$1" "$2" "$3" <<'EOF'
import sys
path, text, replacement = sys.argv[1:4]
s = open(path, encoding="utf-8").read()
if s.count(text) != 1:
    sys.exit(3)
open(path, "w", encoding="utf-8").write(s.replace(text, replacement, 1))
EOF
}

# ---- the list --------------------------------------------------------------------------------
ids=() files=() texts=() repls=() meanings=() notes=()
while IFS= read -r line || [[ -n "$line" ]]; do
  [[ -z "${line//[[:space:]]/}" || "$line" == \#* ]] && continue
  IFS=$'\x1f' read -r id file text repl meaning note <<< "${line//$'\t'/$'\x1f'}"
  if [[ -z "$id" || -z "$file" || -z "$text" || -z "$meaning" ]]; then
    echo "mutation: malformed line in $list: $line" >&2
    exit 2
  fi
  [[ -n "$mutant_regex" ]] && ! grep -Eq -- "$mutant_regex" <<< "$id" && continue
  ids+=("$id") files+=("$file") texts+=("$text") repls+=("$repl") meanings+=("$meaning") notes+=("${note:-}")
done < "$list"
(( ${#ids[@]} > 0 )) || { echo "mutation: no mutant selected" >&2; exit 2; }

if (( check_only )); then
  bad=0
  for i in "${!ids[@]}"; do
    n=$(occurrences "$root/${files[$i]}" "${texts[$i]}" 2> /dev/null || echo "no file")
    if [[ "$n" != 1 ]]; then
      echo "${ids[$i]}: text found $n times in ${files[$i]}"
      bad=1
    fi
  done
  (( bad )) || echo "mutation: all ${#ids[@]} mutants found exactly once"
  exit "$bad"
fi

# ---- the copy: tracked and untracked (not ignored) files; a file is rewritten only when its
# content differs, so unchanged files keep their times and the build stays incremental.
echo "== copying the tree to $src"
mkdir -p "$src" "$logs"
copied=0
while IFS= read -r -d '' f; do
  [[ -f "$root/$f" ]] || continue
  if ! cmp -s "$root/$f" "$src/$f"; then
    mkdir -p "$(dirname "$src/$f")"
    cp "$root/$f" "$src/$f"
    copied=$((copied + 1))
  fi
done < <(git -C "$root" ls-files -z --cached --others --exclude-standard)
echo "   $copied files updated"

# A mutated file is always put back, with a fresh time so that the next build recompiles.
current_file=""
restore() {
  if [[ -n "$current_file" && -f "$current_file.mutation-orig" ]]; then
    cat "$current_file.mutation-orig" > "$current_file"
    rm -f "$current_file.mutation-orig"
  fi
  current_file=""
}
trap restore EXIT
trap 'restore; exit 130' INT TERM
for i in "${!ids[@]}"; do  # left over by a run that was killed harder than a trap can catch
  [[ -f "$src/${files[$i]}.mutation-orig" ]] && { current_file="$src/${files[$i]}"; restore; }
done

# ---- configure, build and the baseline -------------------------------------------------------
# Warnings are not errors here: a mutant that leaves a variable unused is still a behaviour
# to test, not a build failure. No debug information: it doubles the compile time of a test.
generator=()
[[ ! -f "$bld/CMakeCache.txt" ]] && command -v ninja > /dev/null && generator=(-G Ninja)
# No Python module: every mutant of a component header would rebuild its bindings (minutes).
cmake -S "$src" -B "$bld" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -DNDEBUG" -DGYRO_BUILD_TESTS=ON \
  -DGYRO_WERROR=OFF -DGYRO_BUILD_PYTHON=OFF > "$logs/configure.log" 2>&1 || { echo "mutation: configure failed ($logs/configure.log)" >&2; exit 2; }
select_args=()
[[ -n "$test_regex" ]] && select_args+=(-R "$test_regex")
[[ -n "$exclude_regex" ]] && select_args+=(-E "$exclude_regex")
ctest_args=(--test-dir "$bld" -j "$jobs" --no-tests=error "${select_args[@]}")

build() {  # log targets...
  local log="$1"
  shift
  cmake --build "$bld" -j "$jobs" --target "$@" > "$log" 2>&1
}

# The targets of the selected tests: the executables their commands run, when every one is a
# target of this build; otherwise (tests run through cmake -P or python) everything.
targets=()
if [[ -n "$targets_opt" ]]; then
  IFS=',' read -r -a targets <<< "$targets_opt"
elif [[ -z "$test_regex" && -z "$exclude_regex" ]]; then
  targets=(all)
else
  if ctest --test-dir "$bld" -N 2> /dev/null | grep -q '_NOT_BUILT'; then
    echo "== first build of everything (the test lists are known once the tests are built)"
    build "$logs/first-build.log" all || { echo "mutation: build failed ($logs/first-build.log)" >&2; exit 2; }
  fi
  mapfile -t targets < <(ctest --test-dir "$bld" --show-only=json-v1 "${select_args[@]}" |
    "$python" -c '
import json, os, sys
bld = os.path.realpath(sys.argv[1])
names = set()
for t in json.load(sys.stdin).get("tests", []):
    cmd = t.get("command") or [""]
    exe = os.path.realpath(cmd[0])
    if not exe.startswith(bld + os.sep):
        print("all")
        sys.exit(0)
    names.add(os.path.basename(exe))
print("\n".join(sorted(names)) if names else "all")' "$bld")
fi
echo "== baseline: build ${targets[*]}; ctest ${select_args[*]}"
build "$logs/baseline-build.log" "${targets[@]}" || { echo "mutation: the unmutated tree does not build ($logs/baseline-build.log)" >&2; exit 2; }
start=$(date +%s)
if ! ctest "${ctest_args[@]}" > "$logs/baseline-test.log" 2>&1; then
  echo "mutation: the unmutated tree fails its tests ($logs/baseline-test.log): mutants cannot be judged" >&2
  exit 2
fi
baseline_s=$(( $(date +%s) - start ))
[[ -n "$limit" ]] || limit=$(( baseline_s * 5 > 60 ? baseline_s * 5 : 60 ))
tests_run=$(grep -Eo 'tests passed, 0 tests failed out of [0-9]+' "$logs/baseline-test.log" | grep -Eo '[0-9]+$' || echo "?")
echo "   $tests_run tests pass in ${baseline_s}s; a mutant's ctest is stopped after ${limit}s"

# ---- the GoogleTest executables of the selected tests, each with its tests as a filter ------
# (executable, working directory, --gtest_filter): run one at a time before the whole suite.
mapfile -t stages < <(ctest --test-dir "$bld" --show-only=json-v1 "${select_args[@]}" |
  "$python" -c '
import json, os, sys
bld = os.path.realpath(sys.argv[1])
groups = {}
for t in json.load(sys.stdin).get("tests", []):
    cmd = t.get("command") or [""]
    exe = os.path.realpath(cmd[0])
    filt = [a[len("--gtest_filter="):] for a in cmd[1:] if a.startswith("--gtest_filter=")]
    if not exe.startswith(bld + os.sep) or len(filt) != 1:
        continue  # not a discovered GoogleTest case: left to the final ctest
    wd = next((p["value"] for p in t.get("properties", []) if p.get("name") == "WORKING_DIRECTORY"), bld)
    groups.setdefault((exe, wd), []).append(filt[0])
for (exe, wd), names in sorted(groups.items()):
    print("\t".join([exe, wd, ":".join(names)]))' "$bld")
echo "   ${#stages[@]} test executables run before the whole suite, the last killer first"

# Runs the stages for the current mutant; sets result/detail when one kills it and moves that
# executable to the front. The first (the last killer) is built alone, the rest `jobs` at a
# time (a test executable is a few unity translation units: built alone it could leave the
# other cores idle).
# Returns 1 when every stage passed (the whole suite decides).
run_stages() {  # id
  local start=0 size=1 k exe wd filt name rc names
  while (( start < ${#stages[@]} )); do
    names=()
    for ((k = start; k < start + size && k < ${#stages[@]}; ++k)); do
      IFS=$'\t' read -r exe wd filt <<< "${stages[$k]}"
      names+=("$(basename "$exe")")
    done
    if ! build "$logs/$1.build.log" "${names[@]}"; then
      result="build-failed"
      detail="$(grep -m1 -E 'error:' "$logs/$1.build.log" | sed -E 's/^[^ ]*: error: //; s/\|/\\|/g' | cut -c1-100)"
      return 0
    fi
    for ((k = start; k < start + size && k < ${#stages[@]}; ++k)); do
      IFS=$'\t' read -r exe wd filt <<< "${stages[$k]}"
      name="$(basename "$exe")"
      rc=0
      (cd "$wd" && timeout -k 10 "$limit" "$exe" --gtest_filter="$filt" --gtest_brief=1) \
        > "$logs/$1.test.log" 2>&1 || rc=$?
      if (( rc != 0 )); then
        result="killed"
        if (( rc == 124 || rc == 137 )); then
          detail="$name timed out after ${limit}s"
        else
          detail="$(grep -Eo '^\[  FAILED  \] [A-Za-z0-9_/.]+' "$logs/$1.test.log" | sed -E 's/^\[  FAILED  \] //' |
            sort -u | head -3 | paste -sd ' ' -)"
          detail="$name: ${detail:-exit status $rc}"
        fi
        stages=("${stages[$k]}" "${stages[@]:0:$k}" "${stages[@]:$((k + 1))}")
        return 0
      fi
    done
    start=$((start + size))
    size=$jobs
  done
  return 1
}

# Verdicts recorded for this tree and this test selection: every copied file hashed but those
# the build here never reads (scripts/, .ci/, python/: the module is off) and the prose (*.md,
# except docs/scenarios.md, which a test reads).
verdicts="$scratch/verdicts.tsv"
tree_key="$(git -C "$root" ls-files -z --cached --others --exclude-standard |
  grep -zvP '^(scripts|\.ci|python)/|^(?!docs/scenarios\.md$).*\.md$' |
  (cd "$src" && xargs -0 sha1sum 2> /dev/null) | sha1sum | cut -c1-16)"
(( forget )) && rm -f "$verdicts"
touch "$verdicts"
verdict_key() {  # index
  printf '%s\x1f' "$tree_key" "${select_args[@]}" "${files[$1]}" "${texts[$1]}" "${repls[$1]}" |
    sha1sum | cut -c1-16
}

# ---- the mutants -------------------------------------------------------------------------------
results=() details=() times=()
killed=0 survived=0 build_failed=0 refused=0 equivalent=0 reused=0
for i in "${!ids[@]}"; do
  id="${ids[$i]}"
  path="$src/${files[$i]}"
  if [[ -n "${notes[$i]}" && $run_equivalent -eq 0 ]]; then
    results+=("equivalent (not run)") details+=("${notes[$i]#equivalent: }") times+=("")
    equivalent=$((equivalent + 1))
    continue
  fi
  key="$(verdict_key "$i")"
  if [[ -z "${notes[$i]}" ]] && IFS=$'\x1f' read -r _ _ result detail seconds < <(grep -m1 "^$key"$'\x1f' "$verdicts"); then
    reused=$((reused + 1))
    echo "-- $id: $result ${detail:+($detail)} (recorded for this tree)"
  else
    t0=$(date +%s)
    n=$(occurrences "$path" "${texts[$i]}" 2> /dev/null || echo 0)
    if [[ "$n" != 1 ]]; then
      results+=("refused") details+=("text found $n times") times+=("")
      refused=$((refused + 1))
      echo "-- $id: refused (text found $n times in ${files[$i]})"
      continue
    fi
    cp -p "$path" "$path.mutation-orig"
    current_file="$path"
    apply_mutant "$path" "${texts[$i]}" "${repls[$i]}"
    if run_stages "$id"; then
      :
    elif ! build "$logs/$id.build.log" "${targets[@]}"; then
      result="build-failed"
      detail="$(grep -m1 -E 'error:' "$logs/$id.build.log" | sed -E 's/^[^ ]*: error: //; s/\|/\\|/g' | cut -c1-100)"
    else
      rc=0
      timeout -k 10 "$limit" ctest "${ctest_args[@]}" > "$logs/$id.test.log" 2>&1 || rc=$?
      if (( rc == 0 )); then
        result="survived"
        detail=""
      elif (( rc == 124 || rc == 137 )); then
        result="killed"
        detail="timed out after ${limit}s"
      else
        result="killed"
        detail="$(sed -n '/The following tests FAILED/,$p' "$logs/$id.test.log" | grep -E '^\s+[0-9]+ - ' |
          sed -E 's/^\s+[0-9]+ - ([^ ]+).*/\1/' | head -3 | paste -sd ' ' -)"
        nfail=$(grep -Eo '[0-9]+ tests failed' "$logs/$id.test.log" | grep -Eo '^[0-9]+' || echo "?")
        detail="$nfail failed: $detail"
      fi
    fi
    restore
    seconds=$(( $(date +%s) - t0 ))
    [[ -z "${notes[$i]}" ]] && printf '%s\x1f%s\x1f%s\x1f%s\x1f%s\n' "$key" "$id" "$result" "$detail" "$seconds" >> "$verdicts"
    echo "-- $id: $result ${detail:+($detail)} in ${seconds}s"
  fi
  if [[ -n "${notes[$i]}" ]]; then  # run on request (-e): reported, never scored
    [[ "$result" == killed ]] && detail="marked equivalent, yet killed: $detail"
    result="$result (marked equivalent)"
    equivalent=$((equivalent + 1))
  else
    case "$result" in
      killed) killed=$((killed + 1)) ;;
      survived) survived=$((survived + 1)) ;;
      build-failed) build_failed=$((build_failed + 1)) ;;
    esac
  fi
  results+=("$result") details+=("$detail") times+=("$seconds")
done

# ---- report --------------------------------------------------------------------------------------
report() {
  echo "| mutant | file | what it breaks | result | tests that failed / note | s |"
  echo "|---|---|---|---|---|---|"
  for i in "${!ids[@]}"; do
    printf '| %s | %s | %s | %s | %s | %s |\n' "${ids[$i]}" "${files[$i]#component/*/include/gyro/}" \
      "${meanings[$i]}" "${results[$i]}" "${details[$i]}" "${times[$i]}"
  done
  echo
  scored=$((killed + survived))
  if (( scored > 0 )); then
    echo "Score: $killed killed / $scored non-equivalent mutants that built ($(( 100 * killed / scored ))%)."
  else
    echo "Score: no non-equivalent mutant was run."
  fi
  echo "Survived $survived, build-failed $build_failed, refused $refused, equivalent $equivalent" \
    "($reused verdicts recorded for this tree reused);" \
    "tests: ctest ${select_args[*]:-(all)} ($tests_run tests, baseline ${baseline_s}s); logs in $logs."
}
echo
report
[[ -n "$report_file" ]] && report > "$report_file"
(( survived == 0 && build_failed == 0 && refused == 0 )) || exit 1
exit 0
