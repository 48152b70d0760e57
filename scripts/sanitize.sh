#!/usr/bin/env bash
# Builds the host test suite and everything it runs with clang-19 under AddressSanitizer and
# UndefinedBehaviorSanitizer, with source-based coverage and MC/DC of component/ and port/
# (preset host-asan: build/host-asan, -O1 -g1, -fno-sanitize-recover=all, GYRO_SUITE_ONLY: not
# the documentation tools; cmake/coverage-scope.list instruments the two flight libraries only),
# and runs the whole suite with them: any sanitizer report fails its test. The preset turns
# off -Wdeprecated-declarations: clang 19 flags libstdc++ 12's own std::stable_sort (its
# get_temporary_buffer); the host build, GCC, keeps that warning an error. Every test process
# merges its profile into build/host-asan/profiles (LLVM_PROFILE_FILE of the test preset); then
# scripts/coverage_report.py checks the coverage gate (docs/coverage.md) and writes
# build/host-asan/coverage.md (docs/coverage.md too with GYRO_COVERAGE_WRITE_DOC=1:
# scripts/coverage.sh).
# Usage: scripts/sanitize.sh [extra ctest arguments...]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh clang-19 llvm-19 libclang-rt-19-dev
cmake --preset host-asan
cmake --build --preset host-asan
rm -rf build/host-asan/profiles
ctest --preset host-asan "$@"
report=(--build build/host-asan)
if [ "${GYRO_COVERAGE_WRITE_DOC:-0}" = 1 ]; then report+=(--write-doc); fi
/usr/bin/python3 scripts/coverage_report.py "${report[@]}"
