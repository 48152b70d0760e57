#!/usr/bin/env bash
# Builds and tests every cross target, one command each (a CMake workflow preset:
# configure, build, test):
#   cortex-m4f, cortex-m7   bare-metal firmware images under qemu-system-arm (MPS2)
#   aarch64, armhf, ppc, riscv64   the GoogleTest suite of the flight libraries under
#                                  qemu-user (preset cross-linux: the host tools and their
#                                  tests are built and run on the host and under sanitizers)
# then prints the bare-metal footprint table (scripts/footprint.sh), runs the
# processor-in-the-loop checks on both (scripts/pil.sh: 20 to 40 s) and prints each
# target's time.
#
#   scripts/ci-cross.sh [preset...]        (default: all six)
#   CROSS_FRESH=1 scripts/ci-cross.sh      reconfigure from scratch (cmake --fresh)
#
# Needs the Debian packages gcc-arm-none-eabi libstdc++-arm-none-eabi-newlib
# libnewlib-arm-none-eabi qemu-system-arm qemu-user g++-aarch64-linux-gnu
# g++-powerpc-linux-gnu g++-arm-linux-gnueabihf g++-riscv64-linux-gnu (plus cmake, make,
# libeigen3-dev and googletest's sources in /usr/src/googletest).
# Runs every target even when one fails; exits non-zero if any failed.
set -uo pipefail
cd "$(dirname "$0")/.."

presets=("$@")
[ ${#presets[@]} -gt 0 ] || presets=(cortex-m4f cortex-m7 aarch64 armhf ppc riscv64)
fresh=()
[ "${CROSS_FRESH:-0}" = 1 ] && fresh=(--fresh)

summary=()
failed=0
total_start=$(date +%s)
for preset in "${presets[@]}"; do
  echo "=== $preset: cmake --workflow --preset $preset"
  start=$(date +%s)
  if cmake --workflow --preset "$preset" "${fresh[@]}"; then
    result=passed
  else
    result=FAILED
    failed=1
  fi
  summary+=("$(printf '%-11s %-7s %4d s' "$preset" "$result" $(( $(date +%s) - start )))")
done

bare_metal=()
for preset in "${presets[@]}"; do
  case "$preset" in cortex-m4f | cortex-m7) bare_metal+=("$preset") ;; esac
done
if [ ${#bare_metal[@]} -gt 0 ]; then
  echo "=== footprint: scripts/footprint.sh ${bare_metal[*]}"
  start=$(date +%s)
  if scripts/footprint.sh "${bare_metal[@]}"; then result=passed; else result=FAILED; failed=1; fi
  summary+=("$(printf '%-11s %-7s %4d s' footprint "$result" $(( $(date +%s) - start )))")
fi

if [[ " ${bare_metal[*]} " == *" cortex-m4f "* && " ${bare_metal[*]} " == *" cortex-m7 "* ]]; then
  echo "=== processor in the loop: scripts/pil.sh"
  start=$(date +%s)
  if scripts/pil.sh; then result=passed; else result=FAILED; failed=1; fi
  summary+=("$(printf '%-11s %-7s %4d s' pil "$result" $(( $(date +%s) - start )))")
fi

echo "=== cross targets"
printf '%s\n' "${summary[@]}"
echo "total: $(( $(date +%s) - total_start )) s"
exit $failed
