# Field files written by every rank together (parallel HDF5): the same arrays as one rank's,
# the output directory held open by every rank, a kill leaving whole files only.

# pio_fields_run DIR RANKS: the good box for 0.2 s with a frame every step into DIR.
pio_fields_run() {
  local out=$1 ranks=$2
  local -a cmd=("$EMC")
  [ "$ranks" -gt 1 ] && cmd=("${MPIRUN[@]}" -np "$ranks" "$EMC")
  expect_exit 0 "${cmd[@]}" in.xml --set Time/end=0.2 --set Output/every=1 \
    --set Output/progress=false --set Output/plot=false --output "$out"
}

# 2 and 3 ranks, each writing its block of rows, give the 1-rank files: the same mesh.h5, the
# same frames to round-off in the element sums (1e-9 of each array's largest value), the same
# index.
hostile_two_and_three_ranks_write_the_fields_of_one() {
  emc_good_input in.xml
  pio_fields_run one 1 || return 1
  pio_fields_run two 2 || return 1
  "${MPIRUN[@]}" -np 3 "$EMC" in.xml --set Time/end=0.2 --set Output/every=1 \
    --set Output/progress=false --set Output/plot=false --output three >last.out 2>last.err ||
    { echo "3 ranks failed: $(tail -2 last.err)"; return 1; }
  cmp -s one/fields.xdmf two/fields.xdmf && cmp -s one/fields.xdmf three/fields.xdmf ||
    { echo "fields.xdmf differs"; return 1; }
  /usr/bin/python3 - <<'PY'
import glob, os, sys
import h5py, numpy as np
names = sorted(os.path.basename(f) for f in glob.glob('one/*.h5'))
assert 'mesh.h5' in names and len(names) == 22, names  # mesh.h5 and frames 0..20
for other in ('two', 'three'):
    assert sorted(os.path.basename(f) for f in glob.glob(other + '/*.h5')) == names, other
    for n in names:
        a, b = h5py.File('one/' + n, 'r'), h5py.File(other + '/' + n, 'r')
        assert sorted(a) == sorted(b), (other, n, sorted(a), sorted(b))
        for k in a:
            x, y = a[k][()], b[k][()]
            assert a[k].dtype == b[k].dtype and np.shape(x) == np.shape(y), (other, n, k)
            tol = 0 if n == 'mesh.h5' or k in ('step', 'time') else 1e-9 * max(np.max(np.abs(x)), 1e-300)
            d = np.max(np.abs(x - y)) if np.size(x) else 0
            if d > tol:
                sys.exit('%s/%s:%s differs from 1 rank by %g (allowed %g)' % (other, n, k, d, tol))
PY
}

# The output directory swapped for a link while 2 ranks write a frame every step: neither rank
# writes through the link (each holds the directory open), the frames go on in the run's own
# directory, and SIGTERM leaves whole files there.
hostile_two_ranks_fields_not_written_through_a_swapped_directory() {
  emc_good_input in.xml
  mkdir victim
  echo precious >victim/monitors.csv
  "${MPIRUN[@]}" -np 2 "$EMC" in.xml --set Time/end=1000 --set Output/every=1 \
    --set Output/progress=false --set Output/plot=false --output t >run.log 2>&1 &
  local pid=$! i
  for i in $(seq $(($(safety 60) * 10))); do [ -s t/fields_00000002.h5 ] && break; sleep 0.1; done
  [ -s t/fields_00000002.h5 ] || { kill -KILL $pid; echo "the run did not start"; return 1; }
  ln -s victim t.old
  /usr/bin/python3 - <<'PY' || { rm t.old && mv t t.old && ln -s victim t; }
import ctypes
libc = ctypes.CDLL(None, use_errno=True)
AT_FDCWD, RENAME_EXCHANGE = -100, 2
if libc.renameat2(AT_FDCWD, b"t", AT_FDCWD, b"t.old", RENAME_EXCHANGE) != 0:
    raise OSError(ctypes.get_errno(), "renameat2")
PY
  local before
  before=$(ls t.old | grep -c '^fields_0')
  for i in $(seq $(($(safety 60) * 10))); do [ "$(ls t.old | grep -c '^fields_0')" -gt $((before + 2)) ] && break; sleep 0.1; done
  kill -TERM $pid
  local rc=0
  wait $pid || rc=$?
  [ $rc -ne 0 ] || { echo "exit 0 after SIGTERM"; return 1; }
  [ "$(ls -A victim)" = monitors.csv ] && [ "$(cat victim/monitors.csv)" = precious ] ||
    { echo "written through the link: $(ls -A victim)"; return 1; }
  [ "$(ls t.old | grep -c '^fields_0')" -gt $((before + 2)) ] ||
    { echo "no frames after the swap: $(ls t.old | tail -3)"; return 1; }
  ! ls -A t.old | grep -q '\.tmp\.' || { echo "temporaries left: $(ls -A t.old | grep '\.tmp\.')"; return 1; }
  /usr/bin/python3 - <<'PY'
import glob, h5py
for f in glob.glob('t.old/fields_*.h5') + ['t.old/mesh.h5']:
    h5py.File(f, 'r').close()  # every file whole
PY
}

# The last command wrote one error line (mpiexec adds its own report of the exit code).
pio_one_error_line() {
  [ "$(grep -c '^error:' last.err)" = 1 ] || { echo "not one error line:"; head -5 last.err; return 1; }
}

# pio_two_rank_checkpoint: the good box on 2 ranks into ck/, a checkpoint every step; the
# listing of ck/ (names, sizes, times) into the variable `before`.
pio_two_rank_checkpoint() {
  emc_good_input in.xml
  "${MPIRUN[@]}" -np 2 "$EMC" in.xml --set "Output/checkpoint every=1" --set Output/every=1 \
    --set Output/progress=false --set Output/plot=false --output ck >ck.log 2>&1 ||
    { echo "the 2-rank run failed: $(tail -2 ck.log)"; return 1; }
  before=$(cd ck && ls -l --time-style=+%s.%N | md5sum)
}

# DIR/checkpoint.h5 restarted on 3 ranks: refused within 120 s (no hang), with an error
# matching PATTERN, in one line.
pio_refused_on_three() {
  expect_exit_within 120 1 "${MPIRUN[@]}" -np 3 "$EMC" in.xml --set Time/end=0.1 \
    --set Output/progress=false --restart "$1/checkpoint.h5" || return 1
  expect_err "$2" && pio_one_error_line
}

# ck/ as pio_two_rank_checkpoint left it (its listing `before`), and DIR/checkpoint.h5
# restarted on 3 ranks runs to the end.
pio_unchanged_and_runs_on_three() {
  [ "$(cd ck && ls -l --time-style=+%s.%N | md5sum)" = "$before" ] || { echo "ck/ changed"; return 1; }
  expect_exit 0 "${MPIRUN[@]}" -np 3 "$EMC" in.xml --set Time/end=0.1 \
    --set Output/progress=false --set Output/plot=false --restart "$1/checkpoint.h5"
}

# A checkpoint written on 2 ranks, restarted on 3 with another mesh (a longer block) or another
# material: refused before anything is written, one line, on every rank count alike.
hostile_checkpoint_of_two_ranks_for_another_model_refused_on_three() {
  local before
  pio_two_rank_checkpoint || return 1
  expect_exit 1 "${MPIRUN[@]}" -np 3 "$EMC" in.xml --set "Bodies/block/Mesh/upper corner={0.2, 0.1, 0.1}" \
    --set Time/end=0.05 --set Output/progress=false --restart ck/checkpoint.h5 || return 1
  expect_err "ck/checkpoint\.h5: written for another model" && pio_one_error_line || return 1
  expect_exit 1 "${MPIRUN[@]}" -np 3 "$EMC" in.xml --set Bodies/block/Material/young=2e5 \
    --set Time/end=0.05 --set Output/progress=false --restart ck/checkpoint.h5 || return 1
  expect_err "written for another model.*young" && pio_one_error_line || return 1
  [ "$(cd ck && ls -l --time-style=+%s.%N | md5sum)" = "$before" ] || { echo "ck/ changed"; return 1; }
}

# A checkpoint written by 2 ranks together (each its block of u and V), restarted on 3: a piece
# missing (no V) or one value changed in the last rank's block (the checksum, summed along the
# ranks) is refused by every rank with one line before anything is written; the good one runs.
hostile_checkpoint_of_two_ranks_missing_or_changed_piece_refused_on_three() {
  local before
  pio_two_rank_checkpoint || return 1
  cp -r ck no_v && cp -r ck changed || return 1
  /usr/bin/python3 - <<'PY' || return 1
import h5py
with h5py.File('no_v/checkpoint.h5', 'r+') as f:
    del f['V']
with h5py.File('changed/checkpoint.h5', 'r+') as f:
    u = f['u'][:]
    u[-1] += 1e-9  # the last rank's block
    f['u'][:] = u
PY
  pio_refused_on_three no_v "no_v/checkpoint\.h5: not an emcontact checkpoint \(no dataset V\)" &&
    pio_refused_on_three changed "changed/checkpoint\.h5: the checksum does not match the contents" &&
    pio_unchanged_and_runs_on_three ck
}

# A checkpoint written on 2 ranks whose u is stored in checksummed chunks (HDF5's Fletcher-32
# filter), its last chunk corrupted on disk: restarted on 3 ranks, only the last rank reads
# that chunk and fails; every rank stops with its one line (no hang), nothing is written. The
# same file with the chunk intact runs.
hostile_one_rank_failing_to_read_its_block_stops_every_rank() {
  local before
  pio_two_rank_checkpoint || return 1
  cp -r ck chunked && cp -r ck broken || return 1
  /usr/bin/python3 - <<'PY' || return 1
import h5py
def chunked(path):
    with h5py.File(path, 'r+') as f:
        u, attrs = f['u'][:], dict(f['u'].attrs)
        del f['u']
        d = f.create_dataset('u', data=u, chunks=(8,), fletcher32=True)
        for k, v in attrs.items():
            d.attrs[k] = v
        n = d.id.get_num_chunks()
        last = d.id.get_chunk_info(n - 1)
        assert n > 3 and last.chunk_offset[0] >= 2 * len(u) // 3  # in the last rank's block
        return last.byte_offset
chunked('chunked/checkpoint.h5')
offset = chunked('broken/checkpoint.h5')
with open('broken/checkpoint.h5', 'r+b') as f:
    f.seek(offset)
    b = f.read(1)
    f.seek(offset)
    f.write(bytes([b[0] ^ 0xff]))
PY
  pio_refused_on_three broken "broken/checkpoint\.h5: cannot read the checkpoint dataset u" &&
    pio_unchanged_and_runs_on_three chunked
}
