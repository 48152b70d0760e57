#!/usr/bin/env bash
# Flash, RAM and stack on each bare-metal target, as a Markdown table, of two images:
#   component  firmware/footprint/component_tick.cpp (gyro_fw_footprint_component): the
#              flight component behind a register port; init = configure + activate,
#              tick = GyroComponent::step (port read, validation, prediction, estimator,
#              torque law, port write, telemetry)
#   rotor      firmware/footprint/rotor_tick.cpp (gyro_fw_footprint): the exact dynamics
#              alone; init = make_transition, tick = gyro::advance
# each for every bare-metal preset at the preset's -O2 (RelWithDebInfo) and at -Os
# (MinSizeRel), reporting:
#   flash     text + data            (arm-none-eabi-size)
#   RAM       data + bss             (the 64 KiB stack reservation of mps2.ld not counted)
#   gyro code bytes of gyro::/Eigen:: functions in the image (the rest: start-up, libm,
#             libgcc, the output of the stack figures)
#   stack     worst case per call, static bound from GCC's call graph with frame sizes
#             (-fcallgraph-info=su, i.e. the .su figures summed along the deepest path;
#             the port's virtual calls resolved to the image's RegisterPort), and as
#             measured under QEMU by stack painting
#
#   scripts/footprint.sh [preset...]      (default: cortex-m4f cortex-m7)
# Needs: gcc-arm-none-eabi, libnewlib-arm-none-eabi, qemu-system-arm, cmake.
set -euo pipefail
cd "$(dirname "$0")/.."

presets=("$@")
[ ${#presets[@]} -gt 0 ] || presets=(cortex-m4f cortex-m7)

# Static worst-case stack of function $2 from the .ci call graph $1: the largest sum of
# frames along any call path; an indirect call counts as the deepest function whose name
# contains $3 (the port's implementation). Functions without a frame figure (library code
# compiled elsewhere: libm, libgcc) are listed after a '+'. Prints "<bytes>[ + name, name]".
static_stack() {
  awk -v root="$2" -v indirect="${3:-}" '
    /^node:/ {
      title = $0; sub(/.*title: "/, "", title); sub(/".*/, "", title)
      label = $0; sub(/.*label: "/, "", label); sub(/".*/, "", label)
      key = title; sub(/^.*:/, "", key)          # mangled or plain name
      name[title] = key
      if (match(label, /[0-9]+ bytes/)) {
        frame[title] = substr(label, RSTART, RLENGTH) + 0
        if (label ~ /dynamic/) dyn[title] = 1
      } else {
        ext[title] = 1
      }
      if (key == root) start = title
    }
    /^edge:/ {
      s = $0; sub(/.*sourcename: "/, "", s); sub(/".*/, "", s)
      t = $0; sub(/.*targetname: "/, "", t); sub(/".*/, "", t)
      n = ++nout[s]; out[s, n] = t
    }
    function depth(f,    i, d, best, g) {
      if (f in memo) return memo[f]
      if (f == "__indirect_call" && indirect != "") {
        best = 0
        for (g in name) if (index(g, indirect) && !(g in ext)) { d = depth(g); if (d > best) best = d }
        memo[f] = best
        return best
      }
      if (f in ext) { unknown[name[f]] = 1; return 0 }
      if (f in dyn) dynamic = 1
      memo[f] = 0                                 # recursion guard
      best = 0
      for (i = 1; i <= nout[f]; i++) { d = depth(out[f, i]); if (d > best) best = d }
      memo[f] = frame[f] + best
      return memo[f]
    }
    END {
      if (start == "") { print "?"; exit }
      total = depth(start)
      list = ""
      for (u in unknown) list = list (list == "" ? "" : ", ") u
      printf "%d%s%s", total, (dynamic ? " (dynamic)" : ""), (list == "" ? "" : " + " list)
    }' "$1"
}

rows=()
for preset in "${presets[@]}"; do
  case "$preset" in
    cortex-m4f) machine=mps2-an386; cpu="Cortex-M4F"; scalar=float ;;
    cortex-m7)  machine=mps2-an500; cpu="Cortex-M7";  scalar=double ;;
    *) echo "footprint.sh: unknown bare-metal preset '$preset'" >&2; exit 2 ;;
  esac
  for opt in O2 Os; do
    if [ "$opt" = O2 ]; then
      dir="build/$preset"
      cmake --preset "$preset" >/dev/null  # (re)configure: the images may be new to the cache
    else
      dir="build/$preset-minsizerel"
      cmake --preset "$preset" -B "$dir" -DCMAKE_BUILD_TYPE=MinSizeRel >/dev/null
    fi
    cmake --build "$dir" -j2 --target gyro_fw_footprint_component gyro_fw_footprint >/dev/null
    for image in component rotor; do
      if [ "$image" = component ]; then
        target=gyro_fw_footprint_component; source=component_tick; root=gyro_fw_component
      else
        target=gyro_fw_footprint; source=rotor_tick; root=gyro_fw_rotor
      fi
      elf="$dir/firmware/$target.elf"
      ci="$dir/firmware/CMakeFiles/$target.dir/footprint/$source.cpp.ci"
      read -r text data bss _ < <(arm-none-eabi-size "$elf" | awk 'NR == 2')
      gyro_code=$(arm-none-eabi-nm -C -S --defined-only "$elf" | awk '
        function hex(h,    i, v) {
          v = 0; h = tolower(h)
          for (i = 1; i <= length(h); i++) v = v * 16 + index("0123456789abcdef", substr(h, i, 1)) - 1
          return v
        }
        $3 ~ /^[tTwW]$/ && /gyro::|Eigen::/ { s += hex($2) }
        END { print s + 0 }')
      tick_static=$(static_stack "$ci" "${root}_tick" RegisterPort)
      init_static=$(static_stack "$ci" "${root}_init" RegisterPort)
      run=$(qemu-system-arm -M "$machine" -nographic -monitor none -serial none \
              -semihosting-config enable=on,target=native -kernel "$elf" 2>&1) || {
        echo "footprint.sh: $elf failed under QEMU:" >&2; echo "$run" >&2; exit 1; }
      tick_painted=$(echo "$run" | awk '/^stack tick / { print $3 }')
      init_painted=$(echo "$run" | awk '/^stack / && $2 != "tick" { print $3 }')
      rows+=("| $cpu ($scalar) | $image | -$opt | $((text + data)) | $((data + bss)) | $gyro_code | $tick_static | $tick_painted | $init_static | $init_painted |")
    done
  done
done

echo "| target (scalar) | image | opt | flash B (text+data) | RAM B (data+bss) | gyro code B | tick stack B, static | tick stack B, painted | init stack B, static | init stack B, painted |"
echo "|---|---|---|---:|---:|---:|---:|---:|---:|---:|"
printf '%s\n' "${rows[@]}"
echo
echo "component: tick = GyroComponent::step behind a register port, init = configure + activate;"
echo "rotor: tick = gyro::advance (one exact step), init = make_transition. Flash and RAM are the"
echo "whole image (start-up, newlib libm and libgcc included; no heap, the 64 KiB stack not counted)."
echo "Static bounds: GCC -fcallgraph-info=su along the deepest path; '+ name' marks library"
echo "functions (newlib libm) whose own stack is not in the bound; the painted figure, measured"
echo "under QEMU, includes them."
