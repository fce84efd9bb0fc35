#!/usr/bin/env bash
# Kill tests: a run stopped by SIGTERM writes a checkpoint and exits 1 with a message; a run
# killed by SIGKILL leaves a readable monitors.csv and a usable last checkpoint. In both cases
# the restart from the checkpoint runs on. Usage: kill_case.sh EMC COMPARE INPUT OUTDIR [MPIEXEC N]
# With MPIEXEC and N ranks: SIGTERM to mpiexec (which passes it on to the ranks) only, the
# checkpoints written by every rank together, the restart on N ranks too.
set -u
emc=$1 compare=$2 input=$3 out=$4
sigs="TERM KILL"
launch=()
end=0.5  # the restart's Time/end: 100 steps of 0.005
if [ $# -ge 6 ]; then
  launch=("$5" --allow-run-as-root --oversubscribe --mca mpi_yield_when_idle 1 --bind-to none -np "$6")
  sigs=TERM
  end=2  # mpiexec passes the signal on after a delay (up to step 100 seen)
fi
steps=$(awk -v e="$end" 'BEGIN { printf "%d", e / 0.005 + 0.5 }')
fail() { echo "FAIL: $*"; exit 1; }
wait_rows() {  # until monitors.csv has at least $2 data rows (a net of 200 s: ctest allows 300)
  for _ in $(seq 2000); do
    [ -f "$1/monitors.csv" ] && [ "$(($(wc -l < "$1/monitors.csv") - 1))" -ge "$2" ] && return 0
    sleep 0.1
  done
  return 1
}
mkdir -p "$out"
for sig in $sigs; do
  dir=$out/$sig
  rm -rf "$dir"
  "${launch[@]}" "$emc" "$input" --set Time/end=100 --set "Output/checkpoint every=10" \
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
  "${launch[@]}" "$emc" "$input" --set Time/end=100 --set "Output/checkpoint every=10" \
    --set Output/progress=false --set Time/end=$end --output "$dir" --restart "$dir/checkpoint.h5" > "$dir.restart.log" 2>&1 \
    || fail "$sig: restart failed: $(tail -n 2 "$dir.restart.log")"
  after=$(($(wc -l < "$dir/monitors.csv") - 1))
  echo "$sig: $rows rows before the kill, $after after the restart to t = $end"
  [ "$after" -eq $((steps + 1)) ] || fail "$sig: expected $((steps + 1)) rows (steps 0-$steps) after the restart"
done
echo "kill tests passed"
