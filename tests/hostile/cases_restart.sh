# Checkpoints, restarts and the output directory under hostile use: checkpoints of another
# shape or forged behind a recomputed checksum, refused restarts that must leave everything as
# it was, the directory a restart continues in, an output directory renamed during the run,
# messages that name the real cause. run_hostile.sh runs each function in a fresh empty
# directory; every check ends with `|| return 1`.

RST_QUIET=(--set Output/progress=false)

# good_box.xml to step 2 with a checkpoint and a frame every step: ck/.
rst_box_checkpoint() {
  emc_good_input in.xml
  "$EMC" in.xml "${RST_QUIET[@]}" --set Output/every=1 --set "Output/checkpoint every=1" \
    --output ck >ck.log 2>&1 || { tail -3 ck.log; return 1; }
  test -s ck/checkpoint.h5
}

# Two blocks in contact (full stick) checkpointed at step 6 with active entries: ck/.
rst_contact_checkpoint() {
  cp "$HERE/../regression/two_blocks.xml" in.xml
  "$EMC" in.xml "${RST_QUIET[@]}" --set Time/end=0.06 --set "Output/checkpoint every=6" \
    --output ck >ck.log 2>&1 || { tail -3 ck.log; return 1; }
  test -s ck/checkpoint.h5
}

# Every entry of DIR (links not followed) with its checksum: compares a directory before and
# after a command.
rst_snapshot() {
  (cd "$1" && find . -mindepth 1 | sort | while read -r f; do
    if [ -f "$f" ] && [ ! -L "$f" ]; then echo "$(sha256sum <"$f" | cut -c1-16) $f"; else echo "- $f"; fi
  done)
}

# The last step of a monitors.csv.
rst_last_step() {
  tail -1 "$1" | cut -d, -f1
}

# rst_forged_refused EDIT REGEX: a copy f/ of ck/ forged with checkpoint_forge.py EDIT; the
# restart from it is refused in one line naming f/checkpoint.h5 and matching REGEX, exit 1, and
# f/ is left as it was.
rst_forged_refused() {
  rm -rf f && cp -r ck f
  /usr/bin/python3 "$HERE/checkpoint_forge.py" f/checkpoint.h5 "$1" || return 1
  rst_snapshot f >before.txt
  expect_exit_within 60 1 "$EMC" in.xml "${RST_QUIET[@]}" --set Time/end=0.08 --set Output/every=1 \
    --restart f/checkpoint.h5 || return 1
  expect_short_err 1 && expect_err "f/checkpoint\.h5: .*$2" || return 1
  rst_snapshot f | cmp -s - before.txt || { echo "$1: f/ changed"; rst_snapshot f | diff before.txt -; return 1; }
}

# A dataset of another rank than written (u as N x 3, scalars and active as 1 x n) is refused
# naming it before it is read (a 2-dimensional u overflowed the heap: SIGSEGV, aborts, or a
# hang; test_output covers a 2 x 500000 u).
hostile_restart_checkpoint_dataset_of_another_rank_refused() {
  rst_contact_checkpoint || return 1
  local edit
  for edit in u-2d scalars-2d active-2d; do
    rst_forged_refused "$edit" "the checkpoint dataset ${edit%-2d} has 2 dimensions \(allowed: 1" ||
      return 1
  done
}

# The checksum and the model fingerprint stored as arrays of two (read as one value, they
# overflowed the buffer) are refused naming the attribute.
hostile_restart_checkpoint_attribute_array_refused() {
  rst_contact_checkpoint || return 1
  rst_forged_refused checksum-array "the checkpoint attribute checksum is not one 64-bit integer" ||
    return 1
  rst_forged_refused model-array "the checkpoint attribute model is not one string" || return 1
}

# A checkpoint forged behind a recomputed checksum (FNV-1a is not a MAC) with a slave node listed
# twice: refused (the run went on with every contact node counted twice).
hostile_restart_forged_duplicate_entries_refused() {
  rst_contact_checkpoint || return 1
  rst_forged_refused duplicate-entries "active node [0-9]+ is listed twice" || return 1
}

# Forged: every entry at xi = eta = -3, far outside its facet (the run went on penetrating).
hostile_restart_forged_xi_outside_facet_refused() {
  rst_contact_checkpoint || return 1
  rst_forged_refused xi-outside "xi = \(-3, -3\), outside its facet by 3 \(allowed: up to 0\.01" ||
    return 1
}

# Forged: every entry on facet 0, or on the next entry's facet, xi kept inside it (index, xi
# and slave all valid): the slave nodes lie far from their facet points. Accepted, the run went
# on with the nodes held to the wrong facets (gap_min -2.8e-4, penetration).
hostile_restart_forged_entry_on_another_facet_refused() {
  rst_contact_checkpoint || return 1
  local edit
  for edit in facet-zero facet-rotated; do
    rst_forged_refused "$edit" "active node [0-9]+ of pair .* lies [0-9.e+-]+ from its facet [0-9]+'s point" ||
      return 1
  done
}

# The same forgery in a checkpoint of 2 ranks, restarted on 3: each rank checks its own entries
# and every rank stops with the one line.
hostile_restart_forged_entry_on_another_facet_refused_across_ranks() {
  cp "$HERE/../regression/two_blocks.xml" in.xml
  "${MPIRUN[@]}" -np 2 "$EMC" in.xml "${RST_QUIET[@]}" --set Time/end=0.06 \
    --set "Output/checkpoint every=6" --output ck >ck.log 2>&1 || { tail -3 ck.log; return 1; }
  cp -r ck f
  /usr/bin/python3 "$HERE/checkpoint_forge.py" f/checkpoint.h5 facet-rotated || return 1
  expect_exit_within 120 1 "${MPIRUN[@]}" -np 3 "$EMC" in.xml "${RST_QUIET[@]}" \
    --set Time/end=0.08 --restart f/checkpoint.h5 --output g || return 1
  expect_err "f/checkpoint\.h5: the checkpoint's active node [0-9]+ of pair .* from its facet" ||
    return 1
  [ "$(grep -c "active node" last.err)" = 1 ] || { echo "not one line:"; cat last.err; return 1; }
  # the intact checkpoint restarts on 3 ranks
  expect_exit 0 "${MPIRUN[@]}" -np 3 "$EMC" in.xml "${RST_QUIET[@]}" --set Time/end=0.08 \
    --restart ck/checkpoint.h5 --output h || return 1
}

# A checkpoint of another run of the same model (the initial velocity differs: the model
# fingerprint leaves Initial out, as it should) copied over this run's: its u and V disagree
# with the kept monitors row of its step. Accepted, the run continued with the other run's
# state (total energy x14 at the next step, exit 0). As a branch (--output) too.
hostile_restart_checkpoint_of_another_run_refused() {
  cp "$HERE/../../inputs/tumbling_box.xml" in.xml
  "$EMC" in.xml "${RST_QUIET[@]}" --set Time/end=0.03 --set "Output/checkpoint every=2" \
    --output a >a.log 2>&1 || { tail -3 a.log; return 1; }
  "$EMC" in.xml "${RST_QUIET[@]}" --set Time/end=0.03 --set "Output/checkpoint every=2" \
    --set "Bodies/box/Initial/velocity={5, 0, 0}" --output b >b.log 2>&1 || { tail -3 b.log; return 1; }
  cp b/checkpoint.h5 a/checkpoint.h5
  rst_snapshot a >before.txt
  local where
  for where in "" "--output a2"; do
    # shellcheck disable=SC2086
    expect_exit 1 "$EMC" in.xml "${RST_QUIET[@]}" --set Time/end=0.05 --restart a/checkpoint.h5 $where ||
      return 1
    expect_short_err 1 &&
      expect_err "a/checkpoint\.h5: its state's kinetic energy = .* at step 2 disagrees with a/monitors\.csv" ||
      return 1
  done
  rst_snapshot a | cmp -s - before.txt || { echo "a/ changed"; return 1; }
  [ ! -e a2 ] || { echo "the refused branch created a2/"; return 1; }
  expect_exit 0 "$EMC" in.xml "${RST_QUIET[@]}" --set Time/end=0.05 --restart b/checkpoint.h5 || return 1
}

# docs/THEORY.md §12.5: the material model is part of the model's fingerprint: a Neo-Hookean
# run's checkpoint restarted with model svk, or as mooney-rivlin, is refused naming the body's
# model; restarted as it was written, it continues.
hostile_restart_with_another_material_model_refused() {
  cp "$HERE/../regression/two_blocks.xml" in.xml
  local nh=(--set Bodies/A/Material/model=neo-hookean)
  "$EMC" in.xml "${RST_QUIET[@]}" "${nh[@]}" --set Time/end=0.06 --set "Output/checkpoint every=6" \
    --output ck >ck.log 2>&1 || { tail -3 ck.log; return 1; }
  rst_snapshot ck >before.txt
  expect_exit 1 "$EMC" in.xml "${RST_QUIET[@]}" --set Time/end=0.08 --restart ck/checkpoint.h5 ||
    return 1
  expect_short_err 1 && expect_err "ck/checkpoint\.h5: written for another model: .*model neo-hookean" ||
    return 1
  expect_exit 1 "$EMC" in.xml "${RST_QUIET[@]}" --set Bodies/A/Material/model=mooney-rivlin \
    --set Bodies/A/Material/c2=1000 --set Time/end=0.08 --restart ck/checkpoint.h5 || return 1
  expect_err "written for another model: .*mooney-rivlin" || return 1
  rst_snapshot ck | cmp -s - before.txt || { echo "ck/ changed"; return 1; }
  expect_exit 0 "$EMC" in.xml "${RST_QUIET[@]}" "${nh[@]}" --set Time/end=0.08 \
    --restart ck/checkpoint.h5 || return 1
}

# Forged: a time t that is not the time of the checkpoint step's monitors row (t = 1e-300 made
# time go back from step 6 to step 7; t + dt/2 shifted every later row).
hostile_restart_forged_time_refused() {
  rst_contact_checkpoint || return 1
  rst_forged_refused time-early "t = 1e-300 at step 6 disagrees with f/monitors\.csv" || return 1
  rst_forged_refused time-late "t = 0\.065.* at step 6 disagrees with f/monitors\.csv" || return 1
}

# Forged: a step size dt above the Time/dt the checkpoint was written with (dt = 1e300 ran one
# step of the remaining time).
hostile_restart_forged_dt_above_nominal_refused() {
  rst_contact_checkpoint || return 1
  rst_forged_refused dt-huge "dt = 1.*e\+300 is above the Time/dt of its run, 0\.01" || return 1
  rst_forged_refused dt-above-nominal "dt = 0\.02 is above the Time/dt of its run, 0\.01" ||
    return 1
  # the checkpoint as written still restarts
  expect_exit 0 "$EMC" in.xml "${RST_QUIET[@]}" --set Time/end=0.08 --restart ck/checkpoint.h5 ||
    return 1
  [ "$(rst_last_step ck/monitors.csv)" = 8 ] || { echo "ck/monitors.csv ends at $(rst_last_step ck/monitors.csv)"; return 1; }
}

# A refused restart into its own directory writes nothing there (it replaced DIR/mesh.h5 with
# the other model's mesh); once the cause is fixed the same command continues.
hostile_restart_refused_leaves_directory_as_it_was() {
  rst_box_checkpoint || return 1
  rst_snapshot ck >before.txt
  # another model: a longer block (another mesh.h5)
  expect_exit 1 "$EMC" in.xml "${RST_QUIET[@]}" --set Output/every=1 --set Time/end=0.04 \
    --set "Bodies/block/Mesh/upper corner={0.2, 0.1, 0.1}" --restart ck/checkpoint.h5 --output ck || return 1
  expect_short_err 1 && expect_err "ck/checkpoint\.h5: written for another model" || return 1
  rst_snapshot ck | cmp -s - before.txt || { echo "ck/ changed"; rst_snapshot ck | diff before.txt -; return 1; }
  # kept monitors with a gap
  cp ck/monitors.csv monitors.keep
  sed -i '/^1,/d' ck/monitors.csv
  rst_snapshot ck >before.txt
  expect_exit 1 "$EMC" in.xml "${RST_QUIET[@]}" --set Output/every=1 --set Time/end=0.04 \
    --restart ck/checkpoint.h5 || return 1
  expect_short_err 1 && expect_err "ck/monitors\.csv: no row for step 1" || return 1
  rst_snapshot ck | cmp -s - before.txt || { echo "ck/ changed"; rst_snapshot ck | diff before.txt -; return 1; }
  cp monitors.keep ck/monitors.csv
  expect_exit 0 "$EMC" in.xml "${RST_QUIET[@]}" --set Output/every=1 --set Time/end=0.04 \
    --restart ck/checkpoint.h5 || return 1
  [ "$(rst_last_step ck/monitors.csv)" = 4 ] && [ -f ck/fields_00000004.h5 ] ||
    { echo "the corrected restart did not continue in ck: $(ls ck)"; return 1; }
}

# A refused restart into a new directory creates nothing (it left DIR with mesh.h5 and the
# lock, and the corrected retry was refused as "holds the files of an earlier run").
hostile_restart_refused_creates_no_directory() {
  rst_box_checkpoint || return 1
  local opts=("${RST_QUIET[@]}" --set Output/every=1 --set Time/end=0.04 --output nd)
  expect_exit 1 "$EMC" in.xml "${opts[@]}" --restart nonexist/checkpoint.h5 || return 1
  expect_short_err 1 && expect_err "nonexist/checkpoint\.h5" || return 1
  [ ! -e nd ] || { echo "nd created: $(ls -A nd)"; return 1; }
  echo "not HDF5" >junk.h5
  expect_exit 1 "$EMC" in.xml "${opts[@]}" --restart junk.h5 || return 1
  [ ! -e nd ] || { echo "nd created: $(ls -A nd)"; return 1; }
  rm -rf f && cp -r ck f
  /usr/bin/python3 "$HERE/checkpoint_forge.py" f/checkpoint.h5 dt-huge || return 1
  expect_exit 1 "$EMC" in.xml "${opts[@]}" --restart f/checkpoint.h5 || return 1
  [ ! -e nd ] || { echo "nd created: $(ls -A nd)"; return 1; }
  rst_snapshot ck >before.txt
  expect_exit 0 "$EMC" in.xml "${opts[@]}" --restart ck/checkpoint.h5 || return 1
  [ "$(rst_last_step nd/monitors.csv)" = 4 ] || { echo "nd/monitors.csv: $(rst_last_step nd/monitors.csv)"; return 1; }
  rst_snapshot ck | cmp -s - before.txt || { echo "the branch changed ck/"; return 1; }
}

# --restart DIR/checkpoint.h5 without --output continues in DIR, whatever Output/directory says
# (it wrote to Output/directory: DIR kept only the rows before the restart).
hostile_restart_without_output_continues_in_checkpoint_directory() {
  rst_box_checkpoint || return 1
  expect_exit 0 "$EMC" in.xml "${RST_QUIET[@]}" --set Time/end=0.04 --set Output/every=1 \
    --set Output/directory=elsewhere --restart ck/checkpoint.h5 || return 1
  [ ! -e elsewhere ] && [ ! -e output ] || { echo "written elsewhere: $(ls -A)"; return 1; }
  [ "$(rst_last_step ck/monitors.csv)" = 4 ] && [ -f ck/fields_00000004.h5 ] ||
    { echo "ck/ was not continued: $(ls ck)"; return 1; }
  grep -q "output in ck" last.out || { echo "the summary names another directory: $(grep 'output in' last.out)"; return 1; }
}

# The output directory renamed during the run and a link to another directory planted at its
# name: the run goes on writing in the directory it opened (it wrote into the link's target).
hostile_output_directory_renamed_during_run_not_followed() {
  emc_good_input in.xml
  mkdir victim
  echo precious >victim/monitors.csv
  "$EMC" in.xml "${RST_QUIET[@]}" --set Time/end=1000 --set Output/every=0 --output t \
    >run.log 2>&1 &
  local pid=$! i
  for i in $(seq $(($(safety 60) * 10))); do [ -s t/monitors.csv ] && break; sleep 0.1; done
  [ -s t/monitors.csv ] || { kill -KILL $pid; echo "the run did not start"; return 1; }
  # in one step (renameat2 RENAME_EXCHANGE): t becomes the link, the run's directory t.old; a
  # file system without it gets mv and ln (a write in between fails: exit 1, no SIGTERM line)
  ln -s victim t.old
  python3 - <<'PY' || { rm t.old && mv t t.old && ln -s victim t; }
import ctypes
libc = ctypes.CDLL(None, use_errno=True)
AT_FDCWD, RENAME_EXCHANGE = -100, 2
if libc.renameat2(AT_FDCWD, b"t", AT_FDCWD, b"t.old", RENAME_EXCHANGE) != 0:
    raise OSError(ctypes.get_errno(), "renameat2")
PY
  [ -L t ] && [ -d t.old ] && [ ! -L t.old ] || { kill -KILL $pid; echo "the swap failed"; return 1; }
  # SIGTERM: the run writes its checkpoint and flushes its monitors after the swap
  kill -TERM $pid
  local rc=0
  wait $pid || rc=$?
  [ $rc -eq 1 ] && grep -q "stopped by SIGTERM" run.log || { echo "exit $rc: $(tail -2 run.log)"; return 1; }
  [ "$(ls -A victim)" = monitors.csv ] && [ "$(cat victim/monitors.csv)" = precious ] ||
    { echo "written through the link: $(ls -A victim)"; return 1; }
  local step
  step=$(/usr/bin/python3 -c "import h5py; print(int(h5py.File('t.old/checkpoint.h5')['scalars'][0]))") ||
    return 1
  [ "$(rst_last_step t.old/monitors.csv)" = "$step" ] ||
    { echo "t.old/monitors.csv ends at $(rst_last_step t.old/monitors.csv), the checkpoint at $step"; return 1; }
}

# A negative step in the kept monitors is named as such (it was "step -8 given twice").
hostile_restart_negative_monitors_step_named() {
  emc_good_input in.xml
  "$EMC" in.xml "${RST_QUIET[@]}" --set Time/end=0.1 --set "Output/checkpoint every=10" \
    --set Output/every=0 --output m >m.log 2>&1 || return 1
  sed -i 's/^8,/-8,/' m/monitors.csv
  expect_exit 1 "$EMC" in.xml "${RST_QUIET[@]}" --set Time/end=0.2 --restart m/checkpoint.h5 \
    --output mo || return 1
  expect_short_err 1 || return 1
  expect_err "m/monitors\.csv: a row has the negative step -8 \(no row for step 8\)" || return 1
  if grep -q "given twice" last.err; then echo "still 'given twice'"; return 1; fi
  [ ! -e mo ] || { echo "mo created"; return 1; }
}

# A plot that fails for want of space names the cause (the plot script's last line of stderr),
# not matplotlib; the run still ends 0 and leaves no energies.png and no temporary. The file
# size limit of FILE_LIMIT (cases_output.sh: a full disk without privileges) stops the PNG;
# on a full tmpfs the same line reads "No space left on device".
hostile_plot_failure_names_its_cause() {
  /usr/bin/python3 -c 'import matplotlib' 2>/dev/null || { echo "no matplotlib: nothing to check"; return 0; }
  emc_good_input in.xml
  expect_exit 0 "${FILE_LIMIT[@]}" 16 "$EMC" in.xml "${RST_QUIET[@]}" --set Output/every=0 \
    --set Output/plot=true --output out || return 1
  expect_short_err 1 && expect_err "^warning: could not plot out/monitors\.csv.*File too large" ||
    return 1
  if grep -q "matplotlib" last.err; then echo "blamed on matplotlib"; return 1; fi
  [ ! -e out/energies.png ] || { echo "an energies.png was left"; return 1; }
  if ls out | grep -q '\.tmp\.'; then echo "temporary left: $(ls out)"; return 1; fi
}

# A monitors.csv beside the checkpoint that is a link to another file (/etc/passwd): refused
# without quoting that file's text (its first line was copied into the message), the expected
# header cut to the echo limit.
hostile_restart_foreign_monitors_not_quoted() {
  rst_contact_checkpoint || return 1
  printf 'root:x:0:0:secret-line:/root:/bin/bash\n' >other.txt
  rm ck/monitors.csv && ln -s "$PWD/other.txt" ck/monitors.csv
  expect_exit 1 "$EMC" in.xml "${RST_QUIET[@]}" --set Time/end=0.08 --restart ck/checkpoint.h5 \
    --output o || return 1
  expect_short_err 1 && expect_err "ck/monitors\.csv:1: not a monitors file: its header's column 1 is not 'step'" ||
    return 1
  if grep -q "secret-line" last.err; then echo "the file's text was quoted"; return 1; fi
  [ "$(wc -c <last.err)" -lt 400 ] || { echo "too long: $(wc -c <last.err) bytes"; return 1; }
}
