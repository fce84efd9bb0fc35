#!/usr/bin/env bash
# Kill tests: a run stopped by SIGTERM writes a checkpoint and exits 1 with a message; a run
# killed by SIGKILL leaves a readable monitors.csv and a usable last checkpoint. In both cases
# the restart from the checkpoint runs on. Usage: kill_case.sh EMC COMPARE INPUT OUTDIR
set -u
emc=$1 compare=$2 input=$3 out=$4
fail() { echo "FAIL: $*"; exit 1; }
wait_rows() {  # until monitors.csv has at least $2 data rows (a net of 200 s: ctest allows 300)
  for _ in $(seq 2000); do
    [ -f "$1/monitors.csv" ] && [ "$(($(wc -l < "$1/monitors.csv") - 1))" -ge "$2" ] && return 0
    sleep 0.1
  done
  return 1
}
mkdir -p "$out"
for sig in TERM KILL; do
  dir=$out/$sig
  rm -rf "$dir"
  "$emc" "$input" --set Time/end=100 --set "Output/checkpoint every=10" \
    --set Output/progress=false --output "$dir" > "$dir.log" 2>&1 &
  pid=$!
  wait_rows "$dir" 25 || fail "$sig: the run did not get going"
  kill -"$sig" $pid
  wait $pid
  rc=$?
  echo "$sig: exit code $rc; $(tail -n 1 "$dir.log")"
  if [ "$sig" = TERM ]; then
    [ $rc -eq 1 ] || fail "SIGTERM: exit code $rc, expected 1"
    grep -q "stopped by SIGTERM" "$dir.log" || fail "SIGTERM: no message"
  else
    [ $rc -eq 137 ] || fail "SIGKILL: exit code $rc, expected 137"
  fi
  "$compare" "$dir/monitors.csv" "$dir/monitors.csv" 0 0 > /dev/null || fail "$sig: monitors.csv unreadable"
  ls "$dir" | grep -q '\.tmp\.' && echo "note: a temporary file was left by the killed writer (ignored by readers)"
  rows=$(($(wc -l < "$dir/monitors.csv") - 1))
  "$emc" "$input" --set Time/end=100 --set "Output/checkpoint every=10" --set Output/progress=false \
    --set Time/end=0.5 --output "$dir" --restart "$dir/checkpoint.h5" > "$dir.restart.log" 2>&1 \
    || fail "$sig: restart failed: $(tail -n 2 "$dir.restart.log")"
  after=$(($(wc -l < "$dir/monitors.csv") - 1))
  echo "$sig: $rows rows before the kill, $after after the restart to t = 0.5"
  [ "$after" -eq 101 ] || fail "$sig: expected 101 rows (steps 0-100) after the restart"
done
echo "kill tests passed"
