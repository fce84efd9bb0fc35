#!/usr/bin/env bash
# render_ball_impact: runs inputs/ball.xml from 0.05 s before to just past its first impact with
# field output every 5 steps, renders the frame with the most nodes in contact with tools/render_fields.py (whole
# ball, and cut at mid y as in the user guide), checks the PNGs, and checks that a bad field name
# stops the script with exit code 2 and a message.
# Usage: render_case.sh EMC PVPYTHON PYTHON SOURCE_DIR OUTDIR
# Without an X display pvpython runs under xvfb-run; neither there: exit 77 (ctest: skipped).
set -u
emc=$1 pvpython=$2 python=$3 src=$4 out=$5
fail() { echo "FAIL: $*"; exit 1; }
render=$src/tools/render_fields.py
check=$src/tests/render/check_png.py

# Debian's ParaView renders through X only (--force-offscreen-rendering still needs a server).
if [ -z "${DISPLAY:-}" ]; then
  command -v xvfb-run > /dev/null \
    || { echo "SKIP: no X display and no xvfb-run (Debian package xvfb)"; exit 77; }
fi
# xrun CMD...: CMD with an X display: ours, or a fresh Xvfb (xvfb-run) from a random display
# number on (-n before -a): an Xvfb that xvfb-run has just killed may still be exiting, and
# removing its socket, on the display xvfb-run would pick next.
xrun() {
  if [ -n "${DISPLAY:-}" ]; then
    "$@"
  else
    xvfb-run -n $((100 + RANDOM % 800)) -a -s "-screen 0 1280x1024x24" "$@"
  fi
}
# pvr LOG ARGS...: renders; retries twice if the X server was not there.
pvr() {
  local log=$1 rc; shift
  for attempt in 1 2 3; do
    xrun "$pvpython" "$render" "$@" > "$log" 2>&1
    rc=$?
    grep -q "bad X server connection\|Xvfb failed" "$log" || break
    echo "X server not available (attempt $attempt), retrying"
    sleep 2
  done
  return $rc
}

rm -rf "$out"
mkdir -p "$out"
# the ball as it is at t = 0.3 s of its free fall (centre 1 - g 0.3^2 / 2, velocity -0.3 g), so
# that the run starts 0.05 s before the impact instead of flying 0.35 s to it
"$emc" "$src/inputs/ball.xml" --set Time/end=0.09 --set Output/every=5 \
  --set "Bodies/ball/Mesh/center={0, 0, 0.558555}" --set "Bodies/ball/Initial/velocity={2, 0, -2.943}" \
  --set Output/plot=false --set Output/progress=false --output "$out/run" > "$out/run.log" 2>&1
rc=$?
[ $rc -eq 0 ] || { tail -n 20 "$out/run.log"; fail "emcontact exited with $rc"; }
[ -f "$out/run/fields.xdmf" ] || fail "no fields.xdmf"

for view in whole clip; do
  extra=()
  [ $view = clip ] && extra=(--clip)
  pvr "$out/$view.log" "$out/run/fields.xdmf" "$out/$view.png" --at-impact --size 1200x900 \
    --title "inputs/ball.xml" "${extra[@]}"
  rc=$?
  tail -n 20 "$out/$view.log"
  [ $rc -eq 0 ] || fail "render_fields.py ($view) exited with $rc"
  # the frame shown is at the impact (more than 20 nodes in contact, as at step 380 of the full run)
  n=$(sed -n 's/.* \([0-9][0-9]*\) nodes in contact.*/\1/p' "$out/$view.log" | tail -n 1)
  [ -n "$n" ] && [ "$n" -gt 20 ] || fail "$view: the frame rendered is not at the impact (${n:-?} nodes in contact)"
  "$python" "$check" "$out/$view.png" 1200 900 || fail "$view: the PNG check failed"
done

# a field that does not exist: exit code 2 and a message naming it (before any rendering)
"$pvpython" "$render" "$out/run/fields.xdmf" "$out/bad.png" --field no_such_field \
  > "$out/bad.log" 2>&1
rc=$?
cat "$out/bad.log"
[ $rc -eq 2 ] || fail "an unknown field: exit code $rc, expected 2"
grep -q "no field 'no_such_field'" "$out/bad.log" || fail "an unknown field: no message"
[ ! -e "$out/bad.png" ] || fail "an unknown field: a PNG was written"
echo "PASS"
