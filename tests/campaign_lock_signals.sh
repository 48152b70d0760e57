#!/bin/sh
# gyro_campaign's output directory lock under signals (ctest campaign_app_refusals):
#   campaign_lock_signals.sh GYRO_CAMPAIGN LONG_CAMPAIGN.json WORK_DIR
# For SIGINT and SIGTERM: a campaign runs into DIR; while it holds the lock a second one into
# DIR is refused (exit status 2, "in use by another gyro_campaign") and leaves DIR as it was;
# the signal then ends the first with 128 + N, its lock file removed, and a new run can take
# DIR. After SIGKILL the lock file stays but the lock is gone with the process: not refused.
# Prints "ok" on success, else what went wrong (and exits 1).
set -u
exe=$1 campaign=$2 work=$3
fail() { echo "$*"; exit 1; }

# Starts the long campaign into $1 in the background (its signals at their defaults: a
# background job of a non-interactive shell would ignore SIGINT) and waits for its lock and
# for the marker it writes next (DIR as the first campaign keeps it while it runs).
start() {
  env --default-signal=INT,TERM "$exe" run "$campaign" -o "$1" -j 1 -q --no-plots >"$1.out" 2>&1 &
  pid=$!
  i=0
  while [ ! -e "$1/.gyro_campaign.lock" ] || [ ! -e "$1/.gyro_campaign" ]; do
    i=$((i + 1))
    [ $i -gt 200 ] && fail "no lock file in $1 after 10 s"
    kill -0 $pid 2>/dev/null || fail "the first campaign ended early: $(cat "$1.out")"
    sleep 0.05
  done
}

for sig in INT TERM; do
  dir="$work/locked_$sig"
  start "$dir"
  before=$(ls -A "$dir")
  "$exe" run "$campaign" -o "$dir" -j 1 -q --no-plots >"$dir.second" 2>&1
  rc=$?
  [ $rc -eq 2 ] || fail "a second campaign into a locked directory: exit status $rc, expected 2"
  grep -q "is in use by another gyro_campaign (process $pid)" "$dir.second" || fail "second: $(cat "$dir.second")"
  [ "$(ls -A "$dir")" = "$before" ] || fail "the refused campaign changed $dir"
  kill -$sig $pid
  wait $pid
  rc=$?
  case $sig in INT) want=130 ;; TERM) want=143 ;; esac
  [ $rc -eq $want ] || fail "SIG$sig: exit status $rc, expected $want"
  [ -e "$dir/.gyro_campaign.lock" ] && fail "SIG$sig left the lock file"
  leftovers=$(find "$dir" -name '.*.tmp')
  [ -z "$leftovers" ] || fail "SIG$sig left temporaries: $leftovers"
  # The lock is free again.
  start "$dir"
  kill -TERM $pid
  wait $pid
done

dir="$work/killed"
start "$dir"
kill -KILL $pid
wait $pid
[ -e "$dir/.gyro_campaign.lock" ] || fail "expected the lock file to outlive SIGKILL"
start "$dir"
kill -TERM $pid
wait $pid
echo ok
