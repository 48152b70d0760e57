#!/usr/bin/env bash
# Processor-in-the-loop checks (docs/pil.md): the flight component on the emulated target, the
# gyro and the body on the host (gyro_sil --pil), over the serial line, under QEMU -icount.
#   1. seeker slew on the Cortex-M4F (float), 2,000 ticks (the scenario run on past its 1.5 s),
#      with its plot: the CSV matches the host SIL run of the same scenario in float within the
#      tolerances below
#   2. seeker slew on the Cortex-M7 (double), 300 ticks: matches the double SIL run
#   3. overrun: the M4F with a timer period of half a step: the overrun counter rises, ticks
#      are skipped, and the component keeps flying (free, no fault, on the SIL trajectory);
#      run twice: the CSVs, timing columns included, are identical (-icount is deterministic)
#   4. wire faults on the gyro link (crc, drop, duplicate, noise, stall): readings refused and
#      counted exactly in the faulted ticks, duplicates and noise harmless, safe mode when the
#      stall persists
# and prints the figures: exchanges per second, instructions per step (mean, worst and where),
# the largest PIL-vs-host differences. Exits non-zero if any check fails.
#
# The runs are bound by QEMU's serial line (a byte at a time, each after a turn of its main
# loop), not by the CPU: they run side by side, 1, 2 and 4 at once, then the two overrun runs
# (their timer period comes from run 1's step cost).
#
#   scripts/pil.sh            (after scripts/test.sh and the cortex-m4f/cortex-m7 presets, or alone)
# Needs: qemu-system-arm, the arm-none-eabi toolchain, the host build's packages.
set -euo pipefail
cd "$(dirname "$0")/.."

out=build/pil
mkdir -p "$out"
sockets=$(mktemp -d /tmp/gyro-pil.XXXXXX)  # short paths: a UNIX socket path has at most 107 bytes
trap 'wait; rm -rf "$sockets"' EXIT  # runs still going end by themselves (done or timed out)
failed=0
fail() { echo "pil: FAILED: $*"; failed=1; }

echo "== build: gyro_sil (host), gyro_fw_pil (cortex-m4f, cortex-m7)"
# The host build there is (CI's is the preset release), else the preset host.
host=build/host
[ -f "$host/CMakeCache.txt" ] || [ ! -f build/release/CMakeCache.txt ] || host=build/release
[ -f "$host/CMakeCache.txt" ] || cmake --preset host >/dev/null
cmake --build "$host" --target gyro_sil -j2 >/dev/null
for preset in cortex-m4f cortex-m7; do
  [ -f "build/$preset/CMakeCache.txt" ] || cmake --preset "$preset" >/dev/null
  cmake --build "build/$preset" --target gyro_fw_pil -j2 >/dev/null
done
sil=$host/apps/gyro_sil
scenario=scenarios/seeker_slew.json

# pil_run <name> <preset> <machine> <precision> <ticks> [gyro_sil options...]: a PIL run to
# $out/<name>.csv; its progress, the target's console and the PIL summary in $out/<name>.log.
pil_run() {
  local name=$1 preset=$2 machine=$3 precision=$4 ticks=$5
  shift 5
  local start=$SECONDS
  if ! "$sil" "$scenario" --precision "$precision" --ticks "$ticks" -o "$out/$name.csv" \
        --pil "$sockets/$name.sock" --pil-firmware "build/$preset/firmware/gyro_fw_pil.elf" \
        --pil-machine "$machine" "$@" 2> "$out/$name.log"; then
    cat "$out/$name.log"
    fail "$name: gyro_sil --pil exited non-zero"
    return 1
  fi
  echo "$name: $ticks ticks in $((SECONDS - start)) s"
}

# launch <name> <pil_run arguments...>: pil_run in the background, its lines kept for collect.
declare -A pids
launch() {
  local name=$1
  pil_run "$@" > "$out/$name.out" 2>&1 &
  pids[$name]=$!
}

# collect <name>: waits for a launched run and prints its lines; non-zero if it failed.
collect() {
  local rc=0
  wait "${pids[$1]}" || rc=$?
  cat "$out/$1.out"
  [ "$rc" -eq 0 ] || failed=1
  return "$rc"
}

# figures <csv>: instructions per step from the CSV's pil_step_instructions.
figures() {
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
           $c["pil_ran"] == 1 { n++; s += $c["pil_step_instructions"]
             if ($c["pil_step_instructions"] > w) { w = $c["pil_step_instructions"]; at = $c["tick"]; mode = $c["mode"] } }
           END { printf "  step: %d ticks run, %.0f instructions mean, %d worst (tick %d, %s)\n", n, s / n, w, at, mode }' "$1"
}

# compare <sil.csv> <pil.csv> <tolerances>: every column of the SIL CSV in the PIL CSV, row
# by row; columns named in <tolerances> ("name=abs,...") within it, all others identical.
# A toleranced column may also differ by one unit of the CSV's last printed digit (ten
# significant digits: at most 1e-9 of the value): two values an ulp apart can print a digit
# apart (the M7's true rate 8.083557134e-03 against the host's ...135e-03, 1e-12 apart).
compare() {
  awk -F, -v tolerances="$3" '
    BEGIN { n = split(tolerances, pairs, ","); for (i = 1; i <= n; i++) { split(pairs[i], kv, "="); tol[kv[1]] = kv[2] + 0 } }
    NR == FNR { if (FNR == 1) { ncol = NF; for (i = 1; i <= NF; i++) name[i] = $i } else row[FNR] = $0; rows = FNR; next }
    FNR == 1 { for (i = 1; i <= NF; i++) at[$i] = i; next }
    {
      if (!(FNR in row)) { extra++; next }
      split(row[FNR], a, ",")
      for (i = 1; i <= ncol; i++) {
        v = $(at[name[i]])
        if (name[i] in tol) {
          d = a[i] - v; if (d < 0) d = -d
          m = a[i] < 0 ? -a[i] : a[i]; mv = v < 0 ? -v : v; if (mv > m) m = mv
          if (d > tol[name[i]] + 1e-9 * m) beyond[i] = 1
          if (d > worst[i]) { worst[i] = d; where[i] = $(at["tick"]) }
        } else if (a[i] != v) {
          if (!(i in bad)) first[i] = $(at["tick"])
          bad[i]++
        }
      }
    }
    END {
      if (FNR != rows || extra) { printf "  rows: SIL %d, PIL %d\n", rows, FNR; status = 1 }
      for (i = 1; i <= ncol; i++) {
        if (name[i] in tol) {
          over = (i in beyond)
          if (worst[i] > 0 || over) {
            printf("  %-22s max |PIL - host| %.3g (tolerance %g)%s\n", name[i], worst[i], tol[name[i]],
                   (worst[i] > 0 ? sprintf(" at tick %d", where[i]) : ""))
          }
          if (over) status = 1
        } else if (i in bad) {
          printf "  %-22s differs in %d rows (first at tick %d): must be identical\n", name[i], bad[i], first[i]; status = 1
        }
      }
      exit status
    }' "$1" "$2"
}

# Absolute tolerances of the float run (the loop's scales: angles 0.1 rad, rates 0.3 rad/s,
# torques 0.04 N m); every other column (time, mode, flags, request, truth and fault bits,
# step status) must be identical. A float's unit in the last place is 7.5e-9 at 0.1 and 3e-8
# at 0.3: the rate command is held to a few of them. The gimbal plant's true spin-axis rates
# carry its nutation (about 3,800 rad/s: 1e-9 rad of it is 3.8e-6 rad/s): held to 2.5e-4, the
# float host run's own distance from the double one (2.0e-4 rad/s at the uncage, from 6.5e-8
# rad of angles; the plant's sub-steps follow its error estimate, which a torque a few float
# units apart can move by a step). The true cone is an arc cosine of a float
# cosine, one unit of which is 3.5e-4 rad at a zero cone and 6e-7 rad at 0.1 rad: held to
# 1e-3 (the angles it comes from are held to 1e-6). The readings are quantised (one step is
# 6.1e-5 rad): a true angle within 1e-7 of a step's edge reads one step apart, so the readings
# and the residuals are held to one step (6.2e-5) and the estimate, which the estimator gain
# (0.05) moves by 3.1e-6 for such a reading, to 5e-6.
float_tol="gimbal_pitch=1e-6,gimbal_yaw=1e-6,gimbal_pitch_meas=6.2e-5,gimbal_yaw_meas=6.2e-5"
float_tol+=",theta_rate=2e-6,psi_rate=2e-6,torque_pitch=1e-8,torque_yaw=1e-8"
float_tol+=",gimbal_pitch_pred=5e-6,gimbal_yaw_pred=5e-6,residual_pitch=6.2e-5,residual_yaw=6.2e-5"
float_tol+=",theta_rate_true=2.5e-4,psi_rate_true=2.5e-4,rate_cmd_pitch=1e-7,rate_cmd_yaw=1e-7"
float_tol+=",slew_cmd_pitch=0,slew_cmd_yaw=0,nutation_pitch=1e-9,nutation_yaw=1e-9,nutation_pitch_true=1e-9"
float_tol+=",nutation_yaw_true=1e-9,cone_true=1e-3,spin_hz=0,spin_hz_true=0"
float_tol+=",torque_applied_pitch=1e-8,torque_applied_yaw=1e-8,body_pitch_rate=0,body_yaw_rate=0"
double_tol=$(sed 's/=[0-9e.-]*/=1e-12/g' <<< "$float_tol")

"$sil" "$scenario" --precision float --ticks 2000 -o "$out/seeker_slew_sil_float.csv" -q
"$sil" "$scenario" --precision double --ticks 300 -o "$out/seeker_slew_sil_double.csv" -q
all_start=$SECONDS
launch seeker_slew_m4f cortex-m4f mps2-an386 float 2000 --plot "$out/seeker_slew_m4f.png"
launch seeker_slew_m7 cortex-m7 mps2-an500 double 300
launch wire_faults_m4f cortex-m4f mps2-an386 float 1000 \
  --pil-fault crc@600+5 --pil-fault drop@700+5 --pil-fault duplicate@800+10 --pil-fault noise@850+10 \
  --pil-fault stall@900+50

echo "== 1. seeker slew, Cortex-M4F (float), 2,000 ticks: PIL against the host"
if collect seeker_slew_m4f; then
  figures "$out/seeker_slew_m4f.csv"
  compare "$out/seeker_slew_sil_float.csv" "$out/seeker_slew_m4f.csv" "$float_tol" || fail "M4F float run outside tolerance"
  [ -s "$out/seeker_slew_m4f.png" ] || fail "no plot from the PIL run"
fi
mean_clocks=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next } $c["pil_ran"] == 1 { n++; s += $c["pil_step_clocks"] }
                       END { printf "%d", n ? s / n : 200 }' "$out/seeker_slew_m4f.csv" 2>/dev/null || echo 200)
period=$((mean_clocks / 2))
launch overrun_m4f cortex-m4f mps2-an386 float 1000 --pil-tick-clocks "$period"
launch overrun_m4f_again cortex-m4f mps2-an386 float 1000 --pil-tick-clocks "$period"

echo "== 2. seeker slew, Cortex-M7 (double), 300 ticks: PIL against the host"
if collect seeker_slew_m7; then
  figures "$out/seeker_slew_m7.csv"
  compare "$out/seeker_slew_sil_double.csv" "$out/seeker_slew_m7.csv" "$double_tol" || fail "M7 double run outside tolerance"
fi

echo "== 3. overrun: M4F timer period of half a step"
overrun_ok=1
collect overrun_m4f || overrun_ok=0
collect overrun_m4f_again || overrun_ok=0
if [ "$overrun_ok" -eq 1 ]; then
  figures "$out/overrun_m4f.csv"
  awk -F, -v period="$period" '
    NR == FNR { if (FNR == 1) for (i = 1; i <= NF; i++) s[$i] = i; else { gp[FNR] = $s["gimbal_pitch"]; gy[FNR] = $s["gimbal_yaw"] }; next }
    FNR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    { d = gp[FNR] - $c["gimbal_pitch"]; if (d < 0) d = -d; if (d > w) w = d
      d = gy[FNR] - $c["gimbal_yaw"]; if (d < 0) d = -d; if (d > w) w = d
      if (int($c["flags"] / 4096) % 2) gaps++
      if (int($c["flags"] / 16384) % 2) faults++
      last_mode = $c["mode"]; overruns = $c["pil_overruns"]; skipped = $c["pil_skipped"]; ticks = $c["tick"] }
    END {
      printf "  timer %d clocks per tick: %d overruns, %d of %d ticks skipped, %d ticks flagged tick_skipped;\n", period, overruns, skipped, ticks + 1, gaps
      printf "  final mode %s, %d ticks in safe mode; gimbal within %.3g rad of the host run\n", last_mode, faults, w
      # A slew command due in a skipped tick starts with the next tick run: 0.3 rad/s x 1 ms =
      # 3e-4 rad per tick late; 1e-3 rad allows three.
      exit !(overruns > 100 && skipped > 100 && gaps > 100 && last_mode == "free" && faults == 0 && w < 1e-3)
    }' "$out/seeker_slew_sil_float.csv" "$out/overrun_m4f.csv" || fail "overrun: counters, mode or trajectory not as expected"
  if cmp -s "$out/overrun_m4f.csv" "$out/overrun_m4f_again.csv"; then
    echo "  run again: identical CSV (every step's cost, every overrun and skipped tick)"
  else
    fail "overrun: a second run differs from the first"
  fi
fi

echo "== 4. wire faults on the gyro link (M4F): crc, drop, duplicate, noise, stall"
if collect wire_faults_m4f; then
  awk -F, '
    function bit(v, b) { return int(v / b) % 2 }
    NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    {
      k = $c["tick"]; invalid = bit($c["flags"], 8); mode = $c["mode"]
      faulted = (k >= 600 && k < 605) || (k >= 700 && k < 705) || (k >= 900 && k < 950)
      if (k >= 500 && k < 950 && invalid != faulted) { printf "  tick %d: pickoff_invalid %d, expected %d\n", k, invalid, faulted; bad = 1 }
      if (k < 909 && k >= 500 && mode != "free") { printf "  tick %d: mode %s before the stall persisted\n", k, mode; bad = 1 }
      if (k >= 909 && mode != "fault") { printf "  tick %d: mode %s, expected safe mode\n", k, mode; bad = 1 }
      if (k >= 909 && $c["torque_pitch"] != 0) { printf "  tick %d: torque %s in safe mode\n", k, $c["torque_pitch"]; bad = 1 }
      v[k] = $c["pil_crc_errors"] " " $c["pil_bus_errors"] " " $c["pil_timeouts"] " " $c["pil_duplicates"] " " $c["pil_frames_lost"]
      applied[k] = $c["torque_applied_pitch"]
    }
    END {
      expect(604, "5 5 0 0 0"); expect(705, "5 5 5 0 10"); expect(809, "5 5 5 10 10"); expect(860, "5 5 5 10 10")
      expect(949, "5 5 55 10 10"); expect(950, "5 5 55 10 60")
      if (applied[920] == 0) { print "  the stalled link should have left the electronics with their last command"; bad = 1 }
      if (applied[950] != 0) { print "  after the stall the safe-mode zero torque should reach the electronics"; bad = 1 }
      printf "  crc, drop: pickoff_invalid exactly in the 10 faulted ticks; duplicate, noise: no flag;\n"
      printf "  stall: safe mode from tick 909 (10 invalid readings), torquer held by the electronics until the link returns\n"
      printf "  target counters at tick 950 (crc errors, bus errors, timeouts, duplicates, frames lost): %s\n", v[950]
      exit bad
    }
    function expect(k, want) { if (v[k] != want) { printf "  tick %d: counters %s, expected %s\n", k, v[k], want; bad = 1 } }' \
    "$out/wire_faults_m4f.csv" || fail "wire faults: flags, mode or counters not as expected"
fi

grep -h "exchanges/s\|instructions mean" "$out"/seeker_slew_m4f.log "$out"/seeker_slew_m7.log 2>/dev/null | sed 's/^gyro_sil: /  /' || true
echo "the PIL runs took $((SECONDS - all_start)) s side by side"
if [ "$failed" -ne 0 ]; then
  echo "pil: FAILED (outputs in $out/)"
  exit 1
fi
echo "pil: all checks passed (outputs in $out/)"
