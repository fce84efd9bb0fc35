# Output and data-loss cases (security of the output directory, failed writes,
# restarts, locking, the non-empty directory rule). run_hostile.sh runs each function in a fresh
# empty directory; every check ends the case with `|| return 1` (the harness calls the case in a
# condition, where `set -e` does not apply).

EMC_QUIET=(--set Output/progress=false)
# a tumbling box: the monitors change from step to step
EMC_TUMBLE=(--set "Bodies/block/Initial/angular velocity={1,2,3}")

# The plot is run without a shell: quotes, `;`, `$()` and spaces in the directory name stay
# characters (a name that would run `touch pwned` in a shell).
hostile_plot_directory_name_is_not_shell_code() {
  emc_good_input in.xml
  local d1="x'; touch pwned1; echo '" d2="y \$(touch pwned2) \`touch pwned3\`; touch pwned4 '"
  expect_exit 0 "$EMC" in.xml "${EMC_QUIET[@]}" --set Output/plot=true \
    --set "Output/directory=$d1" || return 1
  expect_exit 0 "$EMC" in.xml "${EMC_QUIET[@]}" --set Output/plot=true --output "$d2" || return 1
  local f
  for f in pwned1 pwned2 pwned3 pwned4; do
    [ ! -e "$f" ] || { echo "a command in the output directory's name was run ($f)"; return 1; }
  done
  test -s "$d1/monitors.csv" && test -s "$d2/monitors.csv" || { echo "monitors.csv missing"; return 1; }
  # with matplotlib the plot itself must work on such a name
  if /usr/bin/python3 -c 'import matplotlib' 2>/dev/null; then
    test -s "$d2/energies.png" || { echo "no energies.png in '$d2'"; return 1; }
  fi
}

# Links planted at the old predictable temporary names (<file>.tmp.<pid>, for the next pids)
# must not lead a run to write through them: the file they point to stays unchanged.
hostile_planted_temp_links_are_not_followed() {
  emc_good_input in.xml
  mkdir out
  echo "root's secret" >victim
  chmod 600 victim
  cp -p victim victim.orig
  # one process plants every link (forks would use up the pids it plants for)
  python3 - <<'PY' || return 1
import os
last = int(open('/proc/sys/kernel/ns_last_pid').read())
names = ['monitors.csv', 'mesh.h5', 'fields.xdmf', 'checkpoint.h5'] + \
        ['fields_%08d.h5' % s for s in range(3)]
for pid in range(last + 1, last + 3000):
    for n in names:
        os.symlink('../victim', 'out/%s.tmp.%d' % (n, pid))
PY
  expect_exit 0 "$EMC" in.xml "${EMC_QUIET[@]}" --set Output/every=1 \
    --set "Output/checkpoint every=1" --output out || return 1
  cmp -s victim victim.orig || { echo "victim written through a planted link"; return 1; }
  [ "$(stat -c %a victim)" = 600 ] || { echo "victim's mode changed"; return 1; }
  for f in monitors.csv mesh.h5 fields.xdmf checkpoint.h5 fields_00000002.h5; do
    [ -f "out/$f" ] && [ ! -L "out/$f" ] || { echo "out/$f is not a regular file"; return 1; }
  done
  # a link planted at the lock file is refused, not followed
  rm -rf out2 && mkdir out2 && ln -s ../victim out2/.emcontact.lock
  expect_exit 1 "$EMC" in.xml "${EMC_QUIET[@]}" --output out2 || return 1
  expect_short_err 1 && expect_err "out2" || return 1
  cmp -s victim victim.orig || { echo "victim changed through the lock link"; return 1; }
}

# The file size limit makes writes fail deterministically (EFBIG, SIGXFSZ ignored), like a full
# disk; no privileges needed. Open MPI's own files must not hit the limit: PMIx keeps its data
# in memory (gds hash), one rank needs no shared-memory transport (btl self), and SIGXFSZ is
# not forwarded (else a line on stderr). Usage: "${FILE_LIMIT[@]}" KB CMD...
FILE_LIMIT=(env OMPI_MCA_ess_base_forward_signals=none PMIX_MCA_gds=hash OMPI_MCA_btl=self
            bash -c 'trap "" XFSZ; ulimit -f "$0"; exec "$@"')

# A checkpoint that cannot be written (disk full) keeps the previous one, leaves no temporary,
# stops the run with one line naming the file and exit 1 (no HDF5 dump, no segfault).
hostile_failed_checkpoint_write_keeps_previous() {
  emc_good_input in.xml
  local common=(in.xml "${EMC_QUIET[@]}" --set Output/every=0 --set "Output/checkpoint every=1"
                --set "Bodies/block/Mesh/size=0.02" "${EMC_TUMBLE[@]}")
  expect_exit 0 "$EMC" "${common[@]}" --output out || return 1
  cp out/checkpoint.h5 good.h5
  local kb=$(( $(stat -c %s good.h5) / 1024 / 2 ))
  [ "$(stat -c %s out/monitors.csv)" -lt $((kb * 1024 / 2)) ] || { echo "limit too small"; return 1; }
  expect_exit 1 "${FILE_LIMIT[@]}" "$kb" "$EMC" "${common[@]}" --set Time/end=0.04 \
    --output out --restart out/checkpoint.h5 || return 1
  expect_short_err 1 && expect_err "checkpoint\.h5" || return 1
  cmp -s good.h5 out/checkpoint.h5 || { echo "the previous checkpoint was replaced"; return 1; }
  if ls out | grep -q '\.tmp\.'; then echo "temporary left: $(ls out)"; return 1; fi
}

# The same for the field files: a failed mesh.h5 write stops the run in one line, exit 1.
hostile_failed_field_write_stops_cleanly() {
  emc_good_input in.xml
  expect_exit 1 "${FILE_LIMIT[@]}" 2 "$EMC" in.xml "${EMC_QUIET[@]}" --set Output/every=1 \
    --set "Bodies/block/Mesh/size=0.02" --output out || return 1
  expect_short_err 1 && expect_err "mesh\.h5" || return 1
  if ls out | grep -q '\.tmp\.'; then echo "temporary left: $(ls out)"; return 1; fi
}

# `--restart=` (an empty value, e.g. an unset variable) is refused, not read as "no restart".
hostile_restart_empty_value_refused() {
  emc_good_input in.xml
  expect_exit 1 "$EMC" in.xml "${EMC_QUIET[@]}" --output out --restart= || return 1
  expect_short_err 1 && expect_err "--restart" || return 1
  [ ! -e out/monitors.csv ] || { echo "the run went on from t = 0"; return 1; }
  expect_exit 1 "$EMC" in.xml "${EMC_QUIET[@]}" --output out --restart "" || return 1
  expect_err "--restart" || return 1
}

# An empty output directory (--output "" or Output/directory = "") is refused: never `/`.
hostile_empty_output_directory_refused() {
  emc_good_input in.xml
  expect_exit 1 "$EMC" in.xml "${EMC_QUIET[@]}" --output "" || return 1
  expect_short_err 1 && expect_err "--output" || return 1
  expect_exit 1 "$EMC" in.xml "${EMC_QUIET[@]}" --set "Output/directory=" || return 1
  expect_short_err 1 && expect_err "Output/directory" || return 1
}

# A restart keeps the field frames up to its checkpoint in fields.xdmf and drops the earlier
# run's frames after it (their files removed).
hostile_restart_keeps_earlier_field_frames() {
  emc_good_input in.xml
  local common=(in.xml "${EMC_QUIET[@]}" --set Output/every=1 --set "Output/checkpoint every=2"
                "${EMC_TUMBLE[@]}")
  expect_exit 0 "$EMC" "${common[@]}" --output out || return 1
  cp out/checkpoint.h5 out/step2.h5
  expect_exit 0 "$EMC" "${common[@]}" --set Time/end=0.04 --output out \
    --restart out/checkpoint.h5 || return 1
  [ -f out/fields_00000004.h5 ] || { echo "no frame at step 4"; return 1; }
  expect_exit 0 "$EMC" "${common[@]}" --set Time/end=0.03 --output out \
    --restart out/step2.h5 || return 1
  local listed
  listed=$(grep -o 'Name="step_[0-9]*"' out/fields.xdmf | tr -d '"' | sed 's/Name=//' | xargs)
  [ "$listed" = "step_0 step_1 step_2 step_3" ] || { echo "fields.xdmf lists: $listed"; return 1; }
  [ ! -e out/fields_00000004.h5 ] || { echo "the stale frame of step 4 is still there"; return 1; }
}

# Two runs into one directory: the second one fails at once (also on 2 ranks, every rank
# ends) naming the directory, and the first one's files are left alone.
hostile_two_runs_one_directory_locked() {
  emc_good_input in.xml
  "$EMC" in.xml "${EMC_QUIET[@]}" --set Output/every=0 --set Time/end=1000 --output out \
    >first.log 2>&1 &
  local pid=$! i
  for i in $(seq $(($(safety 60) * 10))); do [ -s out/monitors.csv ] && break; sleep 0.1; done
  [ -s out/monitors.csv ] || { kill -KILL $pid; echo "the first run did not start"; return 1; }
  local rc=0
  expect_exit 1 "${MPIRUN[@]}" -np 2 "$EMC" in.xml "${EMC_QUIET[@]}" --output out || rc=1
  [ $rc -eq 0 ] && { expect_err "out.*in use by another emcontact run" || rc=1; }
  [ $rc -eq 0 ] && { expect_exit 1 "$EMC" in.xml "${EMC_QUIET[@]}" --output out --overwrite || rc=1; }
  [ $rc -eq 0 ] && { expect_short_err 1 && expect_err "in use" || rc=1; }
  kill -0 $pid 2>/dev/null || { echo "the first run died: $(tail -2 first.log)"; rc=1; }
  kill -KILL $pid 2>/dev/null
  wait $pid 2>/dev/null || true
  return $rc
}

# A new run refuses a directory holding an earlier run's files; --overwrite removes exactly
# those (never other files) and runs.
hostile_earlier_run_files_need_overwrite() {
  emc_good_input in.xml
  expect_exit 0 "$EMC" in.xml "${EMC_QUIET[@]}" --set Output/every=1 \
    --set "Output/checkpoint every=1" --output out || return 1
  echo "my notes" >out/notes.txt
  mkdir out/fields_00000099.h5  # a directory with an owned name is not removed either
  cp out/monitors.csv before.csv
  expect_exit 1 "$EMC" in.xml "${EMC_QUIET[@]}" --output out || return 1
  expect_short_err 1 && expect_err "out.*--overwrite" || return 1
  cmp -s before.csv out/monitors.csv || { echo "refused run changed monitors.csv"; return 1; }
  expect_exit 0 "$EMC" in.xml "${EMC_QUIET[@]}" --set Output/every=0 --output out --overwrite || return 1
  [ "$(cat out/notes.txt)" = "my notes" ] && [ -d out/fields_00000099.h5 ] || { echo "a foreign file was removed"; return 1; }
  for f in mesh.h5 fields.xdmf checkpoint.h5 fields_00000000.h5; do
    [ ! -e "out/$f" ] || { echo "out/$f of the earlier run is still there"; return 1; }
  done
  [ -s out/monitors.csv ] || return 1
  "$EMC" --help | grep -q -- "--overwrite" || { echo "--overwrite not in the usage"; return 1; }
}

# A restart into a new, empty --output directory (a branch) reads the checkpoint and its
# monitors where the checkpoint is and gives the rows of the uninterrupted run.
hostile_restart_into_new_directory_branches() {
  emc_good_input in.xml
  # dt and end exact in binary: no clipped last step
  local common=(in.xml "${EMC_QUIET[@]}" --set Output/every=0 --set "Output/checkpoint every=2"
                --set Time/dt=0.0009765625 "${EMC_TUMBLE[@]}")
  expect_exit 0 "$EMC" "${common[@]}" --set Time/end=0.00390625 --output full || return 1
  expect_exit 0 "$EMC" "${common[@]}" --set Time/end=0.001953125 --output half || return 1
  cp half/monitors.csv half.csv
  expect_exit 0 "$EMC" "${common[@]}" --set Time/end=0.00390625 --output branch \
    --restart half/checkpoint.h5 || return 1
  cmp full/monitors.csv branch/monitors.csv || { diff full/monitors.csv branch/monitors.csv | head; return 1; }
  cmp -s half.csv half/monitors.csv || { echo "the branch changed its source's monitors"; return 1; }
}

# HDF5's own error stack is not printed: one line names the file.
hostile_hdf5_error_stack_not_printed() {
  emc_good_input in.xml
  echo "not HDF5" >junk.h5
  expect_exit 1 "$EMC" in.xml "${EMC_QUIET[@]}" --output out --restart junk.h5 || return 1
  expect_short_err 1 && expect_err "junk\.h5" || return 1
  if grep -q "HDF5-DIAG" last.err last.out; then echo "HDF5 error stack printed"; return 1; fi
}

# A monitors.csv that cannot be rewritten (disk full) keeps its previous complete version and
# stops the run in one line naming it, exit 1 (a guard).
hostile_failed_monitors_write_stops_cleanly() {
  emc_good_input in.xml
  expect_exit 1 "${FILE_LIMIT[@]}" 1 "$EMC" in.xml "${EMC_QUIET[@]}" --set Output/every=0 \
    "${EMC_TUMBLE[@]}" --set Time/end=0.1 --output out || return 1
  expect_short_err 1 && expect_err "monitors\.csv" || return 1
  if ls out | grep -q '\.tmp\.'; then echo "temporary left: $(ls out)"; return 1; fi
  [ "$(tail -c 1 out/monitors.csv | od -An -c | tr -d ' ')" = '\n' ] || { echo "monitors.csv cut"; return 1; }
}

# A FIFO planted as monitors.csv next to the checkpoint a restart reads: refused at once (it
# blocked the restart forever), not read.
hostile_restart_monitors_fifo_refused() {
  emc_good_input in.xml
  expect_exit 0 "$EMC" in.xml "${EMC_QUIET[@]}" --set Output/every=0 \
    --set "Output/checkpoint every=1" --output out || return 1
  rm out/monitors.csv && mkfifo out/monitors.csv
  expect_exit 1 "$EMC" in.xml "${EMC_QUIET[@]}" --set Time/end=0.03 --restart out/checkpoint.h5 \
    --output branch || return 1
  expect_short_err 1 && expect_err "monitors.csv.*FIFO" || return 1
}

# --overwrite removes exactly the names a run writes: fields_%08ld.h5 frames and temporaries as
# create_temp names them. A user's fields_0.h5, fields_0000001.h5, a 20-digit "frame" and
# mesh.h5.tmp.x only look like ours (they were deleted).
hostile_overwrite_keeps_files_that_only_look_like_ours() {
  emc_good_input in.xml
  expect_exit 0 "$EMC" in.xml "${EMC_QUIET[@]}" --set Output/every=0 --output ow || return 1
  local n
  for n in fields_0.h5 fields_0000001.h5 fields_99999999999999999999.h5 mesh.h5.tmp.x \
    monitors.csv.tmp.short notes.txt; do echo keep >"ow/$n"; done
  expect_exit 0 "$EMC" in.xml "${EMC_QUIET[@]}" --set Output/every=0 --output ow --overwrite ||
    return 1
  for n in fields_0.h5 fields_0000001.h5 fields_99999999999999999999.h5 mesh.h5.tmp.x \
    monitors.csv.tmp.short notes.txt; do
    [ "$(cat "ow/$n" 2>/dev/null)" = keep ] || { echo "ow/$n was removed or changed"; return 1; }
  done
  # a directory holding only such names is not an earlier run's
  mkdir only && echo keep >only/fields_0.h5
  expect_exit 0 "$EMC" in.xml "${EMC_QUIET[@]}" --set Output/every=0 --output only || return 1
}

# A trailing slash (shell completion adds it) or "/." must not make --output follow a link
# planted at the directory's name: refused as the plain name is, nothing written through it.
hostile_output_link_with_trailing_slash_refused() {
  emc_good_input in.xml
  mkdir real && ln -s real lnk
  local given
  for given in lnk lnk/ lnk// lnk/.; do
    expect_exit 1 "$EMC" in.xml "${EMC_QUIET[@]}" --output "$given" || return 1
    expect_short_err 1 && expect_err "'lnk': it is a symbolic link" || return 1
  done
  [ -z "$(ls -A real)" ] || { echo "written through the link: $(ls -A real)"; return 1; }
  expect_exit 0 "$EMC" in.xml "${EMC_QUIET[@]}" --output real/ || return 1
  test -s real/monitors.csv || return 1
}

# A run whose output cannot fit on the file system (a frame per step for 1e9 steps, about
# 45 TB) is refused before anything is created, naming the estimate and what to change; the
# same run with fields every 1e6 steps is not refused for its fields.
hostile_output_larger_than_the_disk_refused_before_it_starts() {
  emc_good_input in.xml
  expect_exit 1 "$EMC" in.xml "${EMC_QUIET[@]}" --set Time/end=1e7 --set Output/every=1 \
    --output big || return 1
  expect_short_err 1 &&
    expect_err "output directory 'big': the run would write about .* frames of .* more than the .* free there; allowed: .*Output/every" ||
    return 1
  [ ! -e big ] || { echo "big/ was created"; return 1; }
  mkdir old && expect_exit 0 "$EMC" in.xml "${EMC_QUIET[@]}" --output old || return 1
  rst_before=$(cd old && sha256sum monitors.csv)
  expect_exit 1 "$EMC" in.xml "${EMC_QUIET[@]}" --set Time/end=1e7 --set Output/every=1 \
    --output old --overwrite || return 1
  [ "$(cd old && sha256sum monitors.csv)" = "$rst_before" ] || { echo "old/ was overwritten"; return 1; }
}

# fields.xdmf grows by one grid per frame over its closing tags (it was rewritten whole, with an
# fsync, at every frame: O(frames^2)). The index a run leaves is a valid XML document with every
# frame, and the same bytes as a restart's from step 20 (written whole from the frame files up
# to 20, then added to).
hostile_fields_index_grows_by_appending() {
  emc_good_input in.xml
  expect_exit 0 "$EMC" in.xml "${EMC_QUIET[@]}" "${EMC_TUMBLE[@]}" --set Time/end=0.3 \
    --set Output/every=1 --set "Output/checkpoint every=20" --output run || return 1
  /usr/bin/python3 -c "import xml.dom.minidom,sys; d=xml.dom.minidom.parse('run/fields.xdmf'); \
sys.exit(0 if len(d.getElementsByTagName('Time')) == 31 else 1)" || { echo "fields.xdmf: not 31 frames"; return 1; }
  cp run/fields.xdmf appended.xdmf
  expect_exit 0 "$EMC" in.xml "${EMC_QUIET[@]}" "${EMC_TUMBLE[@]}" --set Time/end=0.3 \
    --set Output/every=1 --restart run/checkpoint.h5 || return 1
  cmp -s appended.xdmf run/fields.xdmf || { echo "the appended index differs from the whole one"; return 1; }
}
