# docs/THEORY.md §6.8: a massless slave surface moves its mass onto the body's other nodes by an
# affine fit; a body without nodes off the slave surface that span 3D (a plate one element thick,
# its whole boundary the slave) cannot carry its mass moments: refused before any work, naming
# the file and the pair's parameter.
hostile_massless_slave_without_nodes_behind() {
  expect_exit 1 "$EMC" "$HERE/../regression/bars.xml" --output out \
    "--set=Contact/A on B/massless slave=true" "--set=Bodies/A/Mesh/upper corner={1, 1, 0.05}"
  expect_err "bars.xml: Contact/A on B/massless slave: .*do not span 3D.*allowed: "
  expect_short_err 1
  test ! -e out/monitors.csv
}

# The same on 2 ranks: rank 0 fits (it holds every tet before handing them out), and its refusal
# stops both ranks with the one line, at once (not after the error handler's wait and an abort).
hostile_massless_slave_without_nodes_behind_two_ranks() {
  expect_exit 1 "${MPIRUN[@]}" -np 2 "$EMC" "$HERE/../regression/bars.xml" --output out \
    "--set=Contact/A on B/massless slave=true" "--set=Bodies/A/Mesh/upper corner={1, 1, 0.05}"
  expect_err "bars.xml: Contact/A on B/massless slave: .*do not span 3D.*allowed: "
  # one error line (mpiexec adds its own note on the exit code), no abort
  [ "$(grep -c '^error:' last.err)" = 1 ] || { echo "not one error line:"; head -5 last.err; return 1; }
  ! grep -q MPI_ABORT last.err || { echo "aborted:"; head -5 last.err; return 1; }
  test ! -e out/monitors.csv
}
