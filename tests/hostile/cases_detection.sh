# Contact detection (docs/THEORY.md §6.3, §6.6): a slave node that crosses a master facet deeper
# than the max penetration within a step, bodies that overlap at t = 0, a max penetration below
# the round-off of the gaps, a slave face lying on a tilted rigid plane. Each ran before with
# exit 0 and a wrong result (or refused a good input).

# --- a node crossing a facet deeper than max penetration: the step is cut, else the run stops ---

# The dropped block with dt = 1: in one step it falls 4.9 m, through the rigid ground. With no
# cuts allowed the step cannot be solved: one line naming Time/dt, the speed, max penetration
# (on 1 and 2 ranks).
hostile_crossing_the_ground_in_one_step_stops() {
  cp "$HERE/../regression/drop.xml" in.xml
  for np in 1 2; do
    expect_exit_within 60 1 "${MPIRUN[@]}" -np $np "$EMC" in.xml --set Time/dt=1 \
      --set Time/end=1 --set "Time/max step cuts=0" --output out$np
    expect_err "error: step 1 at t = 0 could not be solved even with dt = 1 .*Time/max step cuts.*273 slave nodes crossed a master facet.*Contact/block on ground/max penetration = 0.1.*approaching at [0-9.]+ m/s.*Time/dt"
    [ "$(grep -c '^error:' last.err)" -eq 1 ] || { echo "not one error line"; return 1; }
  done
}

# With the step cuts, no step is accepted with the block under the ground (it was, at
# com_z = -4.755 by t = 1, exit 0): every row of the monitors keeps com_z above 0, whatever
# ends the run.
hostile_crossing_the_ground_is_cut() {
  cp "$HERE/../regression/drop.xml" in.xml
  local rc=0
  timeout -k 5 "$(safety 120)" "$EMC" in.xml --set Time/dt=1 --set Time/end=1 --output out \
    >last.out 2>last.err || rc=$?
  [ "$rc" -le 1 ] || { echo "exit $rc"; cat last.err; return 1; }
  expect_short_err 1
  awk -F, 'NR > 1 && $19 <= 0 { print "row " NR ": com_z " $19; bad = 1 } END { exit bad }' \
    out/monitors.csv
}

# Block A thrown at 100 m/s at block B (deformable master): it passes through B in one step.
hostile_crossing_a_deformable_master_stops() {
  cp "$HERE/../regression/two_blocks.xml" in.xml
  expect_exit_within 60 1 "$EMC" in.xml --set Time/end=0.1 \
    "--set=Bodies/A/Initial/velocity={100,0,0}" "--set=Bodies/B/Initial/velocity={0,0,0}" \
    --set "Time/max step cuts=0" --output out
  expect_err "slave nodes crossed a master facet and ended deeper behind it than Contact/A on B/max penetration"
  expect_short_err 1
}

# A max penetration below the round-off of a gap on the master can catch nothing: refused at
# input, nothing written.
hostile_max_penetration_below_roundoff_refused() {
  cp "$HERE/../regression/drop.xml" in.xml
  expect_exit_within 30 1 "$EMC" in.xml \
    "--set=Contact/block on ground/max penetration=1e-300" --output out
  expect_err 'parameter "Contact/block on ground/max penetration": value 1e-300 is below the round-off of a gap on the master \(1.8[0-9]e-14\).*allowed: 0 \(automatic\) or a depth from'
  expect_short_err 1
  [ ! -e out ] || { echo "out/ was written"; return 1; }
}

# --- bodies overlapping at t = 0 ---

# A small block A embedded deep inside B (deeper than B's max penetration): its nodes are inside
# the master body. On 2 ranks: one line.
hostile_overlap_slave_embedded_in_master_refused() {
  cp "$HERE/../regression/two_blocks.xml" in.xml
  local sets=("--set=Bodies/A/Mesh/lower corner={0.3, 0.15, 0.1}"
    "--set=Bodies/A/Mesh/upper corner={0.34, 0.19, 0.14}" --set Bodies/A/Mesh/size=0.02
    --set Bodies/B/Mesh/size=0.1)
  for np in 1 2; do
    expect_exit_within 60 1 "${MPIRUN[@]}" -np $np "$EMC" in.xml "${sets[@]}" --output out
    expect_err "error: .*in.xml: Contact/A on B: [0-9]+ slave nodes lie inside the master body at t = 0 \(deepest 0.09[0-9]*, .*the bodies must not overlap"
    [ "$(grep -c '^error:' last.err)" -eq 1 ] || { echo "not one error line"; return 1; }
    [ ! -e out ] || { echo "out/ was written"; return 1; }
  done
}

# The master B inside the slave A: no slave node is inside B, B's nodes are inside A.
hostile_overlap_master_inside_slave_refused() {
  cp "$HERE/../regression/two_blocks.xml" in.xml
  expect_exit_within 60 1 "$EMC" in.xml "--set=Bodies/B/Mesh/lower corner={0.05, 0.05, 0.05}" \
    "--set=Bodies/B/Mesh/upper corner={0.15, 0.15, 0.15}" --set Bodies/B/Mesh/size=0.05 \
    --output out
  expect_err "Contact/A on B: [0-9]+ master nodes lie inside the slave body at t = 0 \(deepest 0.05"
  expect_short_err 1
  [ ! -e out ] || { echo "out/ was written"; return 1; }
}

# Flush faces touch without overlapping (the stack: a cube on a cube on the ground): accepted.
hostile_flush_faces_are_not_an_overlap() {
  cp "$HERE/../regression/stack.xml" in.xml
  expect_exit_within 60 0 "$EMC" in.xml --set Time/end=0.02 --output out
}

# --- a slave face lying on a tilted rigid plane ---

# The puck's bottom face on a plane tilted by 30 and by 7 degrees: its centroid is 1e-17 behind
# the plane by round-off, and it was refused as lying behind. Accepted, E conserved.
hostile_face_on_a_tilted_plane_accepted() {
  cp "$HERE/../regression/tilted_plane.xml" in.xml
  local axis
  for axis in "0.5, 0, 0.8660254037844386" "0.12186934340514748, 0, 0.992546151641322"; do
    expect_exit_within 60 0 "$EMC" in.xml "--set=Bodies/puck/Mesh/axis={$axis}" \
      "--set=Bodies/slope/Mesh/axis={$axis}" --output out --overwrite
    grep -Eq 'max \|E-E0\|/max\(K\+W\+\|Pi\|\) = [0-9.]+e-(1[1-9]|[2-9][0-9])' last.out ||
      { echo "energy error:"; cat last.out; return 1; }
  done
}

# The same face on the plane turned over (its axis away from the puck): the puck lies behind it.
hostile_face_on_a_plane_facing_away_refused() {
  cp "$HERE/../regression/tilted_plane.xml" in.xml
  expect_exit_within 60 1 "$EMC" in.xml "--set=Bodies/slope/Mesh/axis={-0.5, 0, -0.8660254037844386}" \
    --output out
  expect_err "Contact/puck on slope: the slave surface lies on the rigid master at t = 0 facing the same way"
  expect_short_err 1
}

# Time/dt = 1 on the drop: the block crosses the ground within one step; the cut steps then fail
# on an element inverted by the impact. The message names the crossing, the cause, not only the
# inverted element (it read "element 1091 inverted" and nothing else).
hostile_crossing_within_one_step_named_as_the_crossing() {
  cp "$HERE/../regression/drop.xml" in.xml
  expect_exit 1 "$EMC" in.xml --set Output/progress=false --set Time/dt=1 --set Time/end=2 \
    --output o || return 1
  expect_short_err 1 &&
    expect_err "could not be solved .*because at step [0-9]+ with dt = [0-9.e+-]+, [0-9]+ slave nodes crossed a master facet .*Contact/block on ground/max penetration.*a smaller Time/dt" ||
    return 1
}
