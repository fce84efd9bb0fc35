#!/usr/bin/env bash
# Makes docs/ball_impact.png, the user guide's picture: runs inputs/ball.xml to just past its first
# impact (t = 0.39 s, field output every 5 steps, in a temporary directory) and renders, with
# ParaView's pvpython and tools/render_fields.py, the frame with the most nodes in contact, cut
# at the mid y plane and coloured by the von Mises stress.
# Usage (from anywhere, after building): tools/render_readme.sh [BUILD_DIR (default build)]
# Needs the Debian packages paraview and, without a display, xvfb. About a minute.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
emc=$build/bin/emcontact
[ -x "$emc" ] || { echo "no $emc: build first (scripts/build.sh), or name the build directory"; exit 1; }
command -v pvpython > /dev/null || { echo "no pvpython: apt-get install paraview"; exit 1; }
x=()
if [ -z "${DISPLAY:-}" ]; then
  command -v xvfb-run > /dev/null || { echo "no X display and no xvfb-run: apt-get install xvfb"; exit 1; }
  # from a random display number on (-n before -a): an Xvfb that an earlier xvfb-run has just
  # killed may still be exiting, and removing its socket, on the display -a would pick
  x=(xvfb-run -n $((100 + RANDOM % 800)) -a -s "-screen 0 1280x1024x24")
fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "running inputs/ball.xml to t = 0.39 s in $tmp"
"$emc" "$root/inputs/ball.xml" --set Time/end=0.39 --set Output/every=5 --set Output/plot=false \
  --set Output/progress=false --output "$tmp/ball" > "$tmp/run.log" 2>&1 \
  || { tail -n 20 "$tmp/run.log"; echo "emcontact failed"; exit 1; }
mkdir -p "$root/docs"
for attempt in 1 2 3; do  # xvfb-run -a can race with an exiting Xvfb: retry then
  if "${x[@]}" pvpython "$root/tools/render_fields.py" "$tmp/ball/fields.xdmf" \
       "$root/docs/ball_impact.png" --at-impact --clip --size 1200x900 \
       --title "inputs/ball.xml, first impact" > "$tmp/render.log" 2>&1; then
    cat "$tmp/render.log"
    exit 0
  fi
  grep -q "bad X server connection\|Xvfb failed" "$tmp/render.log" || break
  sleep 2
done
cat "$tmp/render.log"
echo "rendering failed"
exit 1
