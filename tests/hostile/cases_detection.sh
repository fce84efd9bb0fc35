# Contact detection (docs/THEORY.md §6.6): bodies that overlap at t = 0, a slave face lying on a
# tilted rigid plane. Each ran before with exit 0 and a wrong result (or refused a good input).

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
    grep -Eq 'max \|E-E0\|/\|E0\| = [0-9.]+e-(1[1-9]|[2-9][0-9])' last.out ||
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
