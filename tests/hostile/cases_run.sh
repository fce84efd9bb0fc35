# Hangs, crashes and silent wrong results: runs that must end (no hang, no
# crash, one line), time steps that cannot advance, SIGTERM, XML depth, untrusted checkpoints,
# solver exceptions, non-regular files, restarts.

# A contact case that gets going in a few steps (two blocks, full stick): $HERE/../regression.
emc_contact_input() {
  cp "$HERE/../regression/two_blocks.xml" "$1"
}

# --- an error on one rank ends every rank (no hang) ---

hostile_two_ranks_output_error_on_rank0_ends_all() {
  emc_good_input in.xml
  echo "not a directory" >dirfile
  expect_exit_within 60 1 "${MPIRUN[@]}" -np 2 "$EMC" in.xml --output dirfile
  expect_err "error: .*dirfile"
}

hostile_two_ranks_output_under_a_file_ends_all() {
  emc_good_input in.xml
  echo "a file" >f
  expect_exit_within 60 1 "${MPIRUN[@]}" -np 2 "$EMC" in.xml --output f/sub
  expect_err "error: .*f/sub"
}

hostile_two_ranks_collective_error_one_line() {  # bad input on 2 ranks: one message, no abort
  emc_good_input in.xml
  expect_exit_within 60 1 "${MPIRUN[@]}" -np 2 "$EMC" in.xml --set Time/dt=-1
  expect_err "Time/dt"
  [ "$(grep -c '^error:' last.err)" -eq 1 ] || { echo "not one error line"; cat last.err; return 1; }
  if grep -q MPI_ABORT last.err; then echo "aborted a collective error"; return 1; fi
}

# --- step sizes that cannot advance time ---

hostile_dt_denormal_refused() {
  emc_good_input in.xml
  expect_exit_within 30 1 "$EMC" in.xml --set Time/dt=4.9e-324 --output out
  expect_err 'parameter "Time/dt".*at most 1e9 steps'
  expect_short_err 1
}

hostile_dt_tiny_with_20_step_cuts_refused() {
  emc_good_input in.xml
  expect_exit_within 30 1 "$EMC" in.xml --set Time/dt=1e-318 --set "Time/max step cuts=20" \
    --output out
  expect_err 'Time/dt'
  expect_short_err 1
}

hostile_dt_huge_refused() {
  emc_good_input in.xml
  expect_exit_within 30 1 "$EMC" in.xml --set Time/dt=1e200 --set Time/end=1e200 --output out
  expect_err 'Time/(dt|end)'
  expect_short_err 1
}

hostile_time_not_finite_refused() {
  emc_good_input in.xml
  expect_exit_within 30 1 "$EMC" in.xml --set Time/end=inf --output out
  expect_err 'Time/end'
  expect_short_err 1
}

# --- SIGTERM: during setup a message (within a long step: cases_solver.sh) ---

# wait_sigterm_caught PID: until PID has its SIGTERM handler (safety 30 s).
wait_sigterm_caught() {
  for _ in $(seq $(($(safety 30) * 10))); do
    local mask
    mask=$(awk '/^SigCgt:/ { print $2 }' "/proc/$1/status" 2>/dev/null) || return 1
    [ -n "$mask" ] && [ $((16#$mask & 0x4000)) -ne 0 ] && return 0
    sleep 0.1
  done
  return 1
}

hostile_sigterm_during_setup_says_so() {
  emc_good_input in.xml
  # a mesh that takes many seconds to generate
  "$EMC" in.xml --set Bodies/block/Mesh/size=0.003 --output out >last.out 2>last.err &
  local pid=$!
  wait_sigterm_caught $pid || true
  sleep 0.5
  kill -TERM $pid
  local rc=0
  wait $pid || rc=$?
  [ "$rc" -eq 1 ] || { echo "exit $rc, expected 1"; cat last.err; return 1; }
  expect_err "stopped by SIGTERM during setup"
  expect_short_err 1
}

# --- XML nesting ---

hostile_xml_nesting_depth_refused() {
  python3 - <<'PY'
n = 10000
with open("deep.xml", "w") as f:
    f.write('<ParameterList name="x">' * n + '</ParameterList>' * n + "\n")
PY
  expect_exit_within 30 1 "$EMC" deep.xml --output out
  expect_err "deep.xml: .*nested more than 64"
  expect_short_err 1
}

# --- untrusted checkpoints ---

# A checkpoint of the contact case with active contact: ck/checkpoint.h5 at step 6.
emc_contact_checkpoint() {
  emc_contact_input in.xml
  "$EMC" in.xml --set Time/end=0.06 --set "Output/checkpoint every=6" --output ck >ck.log 2>&1
  test -s ck/checkpoint.h5
}

hostile_checkpoint_byte_flips_refused_or_identical() {
  emc_contact_checkpoint
  cp -r ck ref
  expect_exit 0 "$EMC" in.xml --set Time/end=0.08 --output ref --restart ref/checkpoint.h5
  local size accepted=0 refused=0
  size=$(stat -c %s ck/checkpoint.h5)
  for k in $(seq 1 20); do
    local pos=$((size * k / 21))
    rm -rf f && cp -r ck f
    python3 -c "
import sys
p, pos = sys.argv[1], int(sys.argv[2])
b = bytearray(open(p, 'rb').read()); b[pos] ^= 0x5a; open(p, 'wb').write(bytes(b))" \
      f/checkpoint.h5 $pos
    local rc=0
    timeout -k 5 "$(safety 60)" "$EMC" in.xml --set Time/end=0.08 --output f --restart f/checkpoint.h5 \
      >last.out 2>last.err || rc=$?
    if [ $rc -eq 0 ]; then
      cmp -s ref/monitors.csv f/monitors.csv || { echo "flip at $pos accepted, other rows"; return 1; }
      accepted=$((accepted + 1))
    elif [ $rc -eq 1 ]; then
      refused=$((refused + 1))
    else
      echo "flip at $pos: exit $rc"; cat last.err; return 1
    fi
  done
  echo "$accepted accepted (identical), $refused refused"
}

# A checkpoint of the good input written every step, with scalar k (0: step, 1: t) of its
# step-2 record (step 2, t 0.02, dt 0.01) replaced by NaN in the file's bytes.
emc_nan_checkpoint_scalar() {
  emc_good_input in.xml
  "$EMC" in.xml --set "Output/checkpoint every=1" --output ck >ck.log 2>&1
  python3 - "$1" <<'PY'
import struct, sys
k = int(sys.argv[1])
p = "ck/checkpoint.h5"
b = bytearray(open(p, "rb").read())
i = b.find(struct.pack("<ddd", 2.0, 0.02, 0.01))
assert i >= 0
b[i + 8 * k:i + 8 * k + 8] = struct.pack("<d", float("nan"))
open(p, "wb").write(bytes(b))
PY
}

hostile_checkpoint_nan_time_refused() {
  emc_nan_checkpoint_scalar 1
  expect_exit_within 30 1 "$EMC" in.xml --set Time/end=0.05 --output ck --restart ck/checkpoint.h5
  expect_err "checkpoint.h5: "
  expect_short_err 1
}

hostile_checkpoint_nan_step_printed_as_number() {
  emc_nan_checkpoint_scalar 0
  expect_exit_within 30 1 "$EMC" in.xml --set Time/end=0.05 --output ck --restart ck/checkpoint.h5
  expect_err "step .*nan"
  if grep -q -- "-9223372036854775808" last.err; then echo "NaN step printed as an integer"; return 1; fi
  expect_short_err 1
}

hostile_checkpoint_of_another_model_refused() {
  emc_good_input in.xml
  "$EMC" in.xml --set "Output/checkpoint every=1" --output ck >ck.log 2>&1
  expect_exit_within 30 1 "$EMC" in.xml --set "Bodies/block/Mesh/upper corner={0.2, 0.1, 0.1}" \
    --set Time/end=0.05 --output ck --restart ck/checkpoint.h5
  expect_err "written for another model"
  expect_short_err 1
  expect_exit_within 30 1 "$EMC" in.xml --set Bodies/block/Material/young=2e5 --set Time/end=0.05 \
    --output ck --restart ck/checkpoint.h5
  expect_err "written for another model.*young"
}

hostile_checkpoint_other_contact_master_refused() {
  emc_contact_checkpoint
  # the master body moves (the "ground"): same sizes, same slave, other coordinates
  expect_exit_within 30 1 "$EMC" in.xml --set "Bodies/B/Mesh/lower corner={0.22, 0.08, 0.05}" \
    --set "Bodies/B/Mesh/upper corner={0.42, 0.28, 0.25}" --set Time/end=0.08 \
    --output ck --restart ck/checkpoint.h5
  expect_err "written for another model"
  expect_short_err 1
}

# docs/THEORY.md §11.7: the sliding block of tests/regression/slide.xml checkpointed at step 60
# (t = 0.3, before it stops), its Coulomb entries sliding: ck/checkpoint.h5 with their states.
emc_sliding_checkpoint() {
  cp "$HERE/../regression/slide.xml" in.xml
  "$EMC" in.xml --set Time/end=0.3 --set "Output/checkpoint every=60" --output ck >ck.log 2>&1
  /usr/bin/python3 "$HERE/checkpoint_state.py" ck/checkpoint.h5 sliding
}

# A checkpoint of the sliding block written before the entries' states were stored
# (pre_state_checkpoint_slide.h5, step 60, with its monitors.csv) still loads: its entries start
# in stick (the return map puts the sliding ones back in slip) and the run goes on.
hostile_checkpoint_without_entry_states_loads() {
  cp "$HERE/../regression/slide.xml" in.xml
  mkdir old
  cp "$HERE/pre_state_checkpoint_slide.h5" old/checkpoint.h5
  cp "$HERE/pre_state_checkpoint_slide.csv" old/monitors.csv
  expect_exit_within 120 0 "$EMC" in.xml --set Time/end=0.35 --output old \
    --restart old/checkpoint.h5 || return 1
  [ "$(wc -l <old/monitors.csv)" -eq 72 ] || { echo "not 71 steps"; return 1; }
  cmp -s <(head -62 old/monitors.csv) "$HERE/pre_state_checkpoint_slide.csv" ||
    { echo "the rows up to the checkpoint changed"; return 1; }
}

# Entry states of a wrong size or with values a run cannot have written are refused, naming the
# file and what is wrong; a state edited without its checksum is refused as corrupt.
hostile_checkpoint_bad_entry_states_refused() {
  emc_sliding_checkpoint || return 1
  local edit want
  for edit in drop-last slip-2 slip-no-direction dir-nan off-while-sliding flip-slip; do
    case $edit in
      drop-last) want="dataset state has [0-9]+ values \\(allowed: 0 or [0-9]+, 5 per active node" ;;
      slip-2) want="slip = 2.* \\(allowed: 0 or 1\\)" ;;
      slip-no-direction) want="slip = 1 with a direction of length 0" ;;
      dir-nan) want="slip direction of length (nan|-nan)" ;;
      off-while-sliding) want="off = 1 but is not a sticking coulomb entry" ;;
      flip-slip) want="" ;;
    esac
    rm -rf f && cp -r ck f
    /usr/bin/python3 "$HERE/checkpoint_state.py" f/checkpoint.h5 $edit || return 1
    if [ -z "$want" ]; then  # a valid state (stick): accepted
      expect_exit_within 120 0 "$EMC" in.xml --set Time/end=0.31 --output f \
        --restart f/checkpoint.h5 || return 1
      continue
    fi
    expect_exit_within 30 1 "$EMC" in.xml --set Time/end=0.31 --output f \
      --restart f/checkpoint.h5 || return 1
    expect_err "f/checkpoint.h5: .*$want" || return 1
    expect_short_err 1 || return 1
  done
  rm -rf f && cp -r ck f
  /usr/bin/python3 "$HERE/checkpoint_state.py" f/checkpoint.h5 flip-slip --keep-checksum
  expect_exit_within 30 1 "$EMC" in.xml --set Time/end=0.31 --output f --restart f/checkpoint.h5
  expect_err "f/checkpoint.h5: the checksum does not match"
}

# --- solver exceptions ---

hostile_belos_num_blocks_zero_one_line() {
  emc_good_input in.xml
  expect_exit_within 30 1 "$EMC" in.xml --set "Solver/Linear/Belos/Num Blocks=0" --output out
  expect_err 'Solver/Linear/Belos.*Num Blocks'
  expect_short_err 1
}

hostile_ifpack2_bad_value_one_line() {
  emc_good_input in.xml
  # ILU named: on a threaded backend `auto` takes Chebyshev, which ignores ILU's parameters
  expect_exit_within 30 1 "$EMC" in.xml --set Solver/Linear/preconditioner=ilu \
    --set "Solver/Linear/Ifpack2/fact: iluk level-of-fill=abc" --output out
  expect_err 'Solver/Linear/Ifpack2'
  expect_short_err 1
}

hostile_young_1e308_refused_naming_it() {
  emc_good_input in.xml
  expect_exit_within 60 1 "$EMC" in.xml --set Bodies/block/Material/young=1e308 \
    --set "Bodies/block/Initial/velocity={1,0,0}" \
    --set "Bodies/block/Initial/angular velocity={0,0,5}" --output out
  expect_err 'override "Bodies/block/Material/young=1e308": value 1e308 is out of range'
  expect_short_err 1
  if grep -q "Throw number" last.err; then echo "a Trilinos dump"; return 1; fi
}

hostile_pass_through_typos_warned() {
  emc_good_input in.xml
  expect_exit_within 60 0 "$EMC" in.xml --set "Solver/Linear/Belos/Maximum Iteratons=5" \
    --set "Solver/Linear/Ifpack2/fact: iluk levl-of-fill=1" --output out
  expect_err 'warning: .*Belos.*"Maximum Iteratons"'
  expect_err 'warning: .*Ifpack2.*"fact: iluk levl-of-fill"'
}

hostile_ifpack2_parameters_of_another_preconditioner_warned() {
  emc_good_input in.xml
  expect_exit_within 60 0 "$EMC" in.xml --set Solver/Linear/preconditioner=chebyshev \
    --set "Solver/Linear/Ifpack2/fact: iluk level-of-fill=1" --output out
  expect_err 'warning: .*Ifpack2.*"fact: iluk level-of-fill" not read by chebyshev'
  expect_exit_within 60 0 "$EMC" in.xml --set Solver/Linear/preconditioner=ilu \
    --set "Solver/Linear/Ifpack2/chebyshev: degree=4" --output out2
  expect_err 'warning: .*Ifpack2.*"chebyshev: degree" not read by ilu'
}

# --- files that are not regular files ---

hostile_fifo_input_refused() {
  mkfifo in.xml
  expect_exit_within 30 1 "$EMC" in.xml --output out
  expect_err "in.xml: .*FIFO.*not a regular file"
  expect_short_err 1
}

hostile_directory_and_device_input_refused() {
  mkdir in.xml
  expect_exit_within 30 1 "$EMC" in.xml --output out
  expect_err "in.xml: .*directory, not a regular file"
  expect_exit_within 30 1 "$EMC" /dev/zero --output out
  expect_err "/dev/zero: .*device, not a regular file"
  expect_short_err 1
}

hostile_fifo_restart_refused() {
  emc_good_input in.xml
  mkfifo ck.h5
  expect_exit_within 30 1 "$EMC" in.xml --output out --restart ck.h5
  expect_err "ck.h5: .*FIFO.*not a regular file"
  expect_short_err 1
}

hostile_mesh_file_not_regular_refused() {
  emc_good_input in.xml
  mkdir m.msh
  mkfifo p.msh
  for m in m.msh p.msh /dev/zero; do
    expect_exit_within 30 1 "$EMC" in.xml --set Bodies/block/Mesh/type=file \
      --set "Bodies/block/Mesh/file=$m" --output out
    expect_err "not a regular file"
    if grep -q "does not exist" last.err; then echo "$m: says does not exist"; return 1; fi
    expect_short_err 1
  done
}

# --- restarts that would silently differ ---

hostile_restart_changed_dt_applied() {
  emc_good_input in.xml
  "$EMC" in.xml --set "Output/checkpoint every=1" --output ck >ck.log 2>&1
  expect_exit 0 "$EMC" in.xml --set Time/dt=0.005 --set Time/end=0.04 --output ck \
    --restart ck/checkpoint.h5
  expect_err "Time/dt changed from 0.01.* to 0.005.*from step 3 on"
  # rows after the checkpoint (steps 3..) have dt 0.005
  awk -F, 'NR > 4 && $15 != 0.005 { bad = 1; print } END { exit bad }' ck/monitors.csv
  [ "$(tail -1 ck/monitors.csv | cut -d, -f1)" = 6 ]
}

hostile_restart_past_end_refused() {
  emc_good_input in.xml
  "$EMC" in.xml --set "Output/checkpoint every=1" --output ck >ck.log 2>&1
  expect_exit_within 30 1 "$EMC" in.xml --output ck --restart ck/checkpoint.h5
  expect_err "at or past Time/end"
  expect_short_err 1
}

hostile_restart_monitors_missing_row_refused() {
  emc_good_input in.xml
  "$EMC" in.xml --set Time/end=0.04 --set "Output/checkpoint every=4" --output ck >ck.log 2>&1
  sed -i '/^2,/d' ck/monitors.csv
  expect_exit_within 30 1 "$EMC" in.xml --set Time/end=0.06 --output ck --restart ck/checkpoint.h5
  expect_err "monitors.csv: no row for step 2"
  expect_short_err 1
}

# --- messages ---

hostile_long_refused_value_truncated() {
  emc_good_input good.xml
  python3 - <<'PY'
s = open("good.xml").read()
long = '<Parameter name="integrator" type="string" value="' + "x" * 1000000 + '"/>'
open("in.xml", "w").write(s.replace('<ParameterList name="Time">', '<ParameterList name="Time">' + long, 1))
PY
  expect_exit_within 30 1 "$EMC" in.xml --output out
  expect_err 'Time/integrator'
  local bytes
  bytes=$(wc -c <last.err)
  [ "$bytes" -lt 2000 ] || { echo "stderr has $bytes bytes"; return 1; }
}

# --- restarts identical to the uninterrupted run ---

hostile_restart_after_sigterm_identical() {
  emc_contact_input in.xml
  local opts=(--set Time/end=0.3 --set "Output/checkpoint every=4")
  expect_exit 0 "$EMC" in.xml "${opts[@]}" --output A
  "$EMC" in.xml "${opts[@]}" --output C >c.log 2>&1 &
  local pid=$!
  for _ in $(seq $(($(safety 30) * 20))); do
    [ -f C/monitors.csv ] && [ "$(wc -l <C/monitors.csv)" -ge 8 ] && break
    sleep 0.05
  done
  kill -TERM $pid
  local rc=0
  wait $pid || rc=$?
  echo "SIGTERM: exit $rc: $(tail -1 c.log)"
  [ "$rc" -eq 1 ] || return 1
  expect_exit 0 "$EMC" in.xml "${opts[@]}" --output C --restart C/checkpoint.h5
  cmp A/monitors.csv C/monitors.csv
}

hostile_extended_run_identical() {
  emc_contact_input in.xml
  # 8 steps of 0.01 sum to 0.08 - 5e-18: the last step to end = 0.08 is dt within round-off
  expect_exit 0 "$EMC" in.xml --set Time/end=0.12 --set "Output/checkpoint every=8" --output A
  expect_exit 0 "$EMC" in.xml --set Time/end=0.08 --set "Output/checkpoint every=8" --output B
  expect_exit 0 "$EMC" in.xml --set Time/end=0.12 --set "Output/checkpoint every=8" --output B \
    --restart B/checkpoint.h5
  cmp A/monitors.csv B/monitors.csv
}

# --- contact parameters whose scale silently disabled contact ---

hostile_max_penetration_beyond_master_refused() {
  cp "$HERE/../regression/drop.xml" in.xml
  expect_exit_within 30 1 "$EMC" in.xml --set "Contact/block on ground/max penetration=1e100" \
    --output out
  expect_err 'parameter "Contact/block on ground/max penetration".*larger than the master'
  expect_short_err 1
}

hostile_huge_rigid_plane_refused() {
  cp "$HERE/../regression/drop.xml" in.xml
  expect_exit_within 30 1 "$EMC" in.xml --set "Bodies/ground/Mesh/half width=1e100" --output out
  expect_err 'parameter "Bodies/ground/Mesh".*more than 1e6 times'
  expect_short_err 1
}

# A checkpoint of good_box.xml at step 2 written before checkpoints had a fingerprint and a
# checksum (old_checkpoint_good_box.h5, with its monitors.csv): refused, saying why.
hostile_checkpoint_without_fingerprint_refused() {
  emc_good_input in.xml
  mkdir old
  cp "$HERE/old_checkpoint_good_box.h5" old/checkpoint.h5
  cp "$HERE/old_checkpoint_good_box.csv" old/monitors.csv
  expect_exit_within 30 1 "$EMC" in.xml --set Time/end=0.04 --output old \
    --restart old/checkpoint.h5
  expect_err "old/checkpoint.h5: written by an older emcontact"
  expect_short_err 1
}

hostile_long_override_truncated() {
  emc_good_input in.xml
  local long
  long=$(python3 -c 'print("x" * 100000)')
  for o in "Time/integrator=$long" "Time/dt=9$long" "Time/$long=1" "$long/a=1"; do
    expect_exit_within 30 1 "$EMC" in.xml --set "$o" --output out
    expect_short_err 1
    local bytes
    bytes=$(wc -c <last.err)
    [ "$bytes" -lt 2000 ] || { echo "stderr has $bytes bytes for --set ${o:0:20}..."; return 1; }
  done
}

# A malformed value of one of Kokkos' own options aborted (an uncaught std::invalid_argument
# from Kokkos::initialize: exit 134 and Open MPI's backtrace banner): one line naming the
# option, exit 1, on 1 and 2 ranks.
hostile_malformed_kokkos_option_one_line() {
  emc_good_input in.xml
  local o
  for o in --kokkos-threads=abc --kokkos-threads=-5 --kokkos-threads=99999999999 \
    --kokkos-numa=abc --kokkos-threads --kokkos-ndevices=2,x --threads=abc; do
    expect_exit 1 "$EMC" in.xml --set Output/progress=false "$o" --output k || return 1
    expect_short_err 1 && expect_err "^error: Kokkos option \"${o%%=*}.*allowed: " || return 1
  done
  expect_exit 1 "${MPIRUN[@]}" -np 2 "$EMC" in.xml --kokkos-threads=abc --output k || return 1
  [ "$(grep -c '^error: ' last.err)" = 1 ] && expect_err "Kokkos option \"--kokkos-threads=abc\"" ||
    { echo "not one line:"; cat last.err; return 1; }
  if grep -q "Signal: Aborted\|terminate called" last.err; then cat last.err; return 1; fi
  [ ! -e k ] || { echo "k/ was created"; return 1; }
  expect_exit 0 "$EMC" in.xml --set Output/progress=false --kokkos-threads=1 --output k || return 1
}

# Names no --set, message or output can address are refused naming the list: empty, holding
# '/', a newline, invalid UTF-8 (each ran, exit 0; "A/xmax" was then suggested as the value it
# refused).
hostile_unaddressable_names_refused() {
  emc_contact_input two.xml
  sed 's|name="B"|name="A/xmax"|; s|value="B"/>|value="A/xmax"/>|' two.xml >slash.xml
  expect_exit 1 "$EMC" slash.xml || return 1
  expect_short_err 1 && expect_err "slash\.xml: parameter \"Bodies\": .*\"A/xmax\" holds '/'" || return 1
  emc_good_input in.xml
  sed 's|name="block"|name=""|' in.xml >empty.xml
  expect_exit 1 "$EMC" empty.xml || return 1
  expect_short_err 1 && expect_err "empty\.xml: parameter \"Bodies\": .*an empty name" || return 1
  sed 's|name="block"|name="a\&#10;b"|' in.xml >newline.xml
  expect_exit 1 "$EMC" newline.xml || return 1
  expect_short_err 1 && expect_err "newline\.xml: .*\"a\\\\nb\" holds a control character" || return 1
  printf 's|name="block"|name="b\xff\xfex"|' >s.sed && sed -f s.sed in.xml >latin.xml
  expect_exit 1 "$EMC" latin.xml || return 1
  expect_short_err 1 && expect_err "latin\.xml: cannot read the input: byte [0-9]+ \(line 9, 0xff\) is not UTF-8" ||
    return 1
  # UTF-8 names are fine
  sed 's|name="block"|name="blöck"|' in.xml >utf8.xml
  expect_exit 0 "$EMC" utf8.xml --set Output/progress=false --output u || return 1
}

# body/boundary names the body's whole boundary as a contact surface, as the guide says (it was
# refused: 'body "B" has no surface "boundary"'); the run is the one of the body's name alone.
hostile_body_boundary_is_a_contact_surface() {
  emc_contact_input two.xml
  expect_exit 0 "$EMC" two.xml --set Output/progress=false --set Time/end=0.03 \
    "--set=Contact/A on B/master=B/boundary" --output slash || return 1
  expect_exit 0 "$EMC" two.xml --set Output/progress=false --set Time/end=0.03 \
    "--set=Contact/A on B/master=B" --output whole || return 1
  cmp -s slash/monitors.csv whole/monitors.csv || { echo "B/boundary is not B"; return 1; }
  expect_exit 1 "$EMC" two.xml --set Time/end=0.03 "--set=Contact/A on B/master=B/bound" || return 1
  expect_short_err 1 && expect_err "no surface \"bound\"; its surfaces: .* and \"boundary\"" || return 1
}

# The same option twice took the last one silently. --output and --restart twice are refused
# naming both (which directory was meant is not for the run to guess); a --set of one parameter
# twice is said in one warning and the last one applies (a wrapper script's default overridden
# on its own command line, as with make VAR=...).
hostile_repeated_options_refused_or_warned() {
  emc_good_input in.xml
  expect_exit 1 "$EMC" in.xml --output o1 --output o2 || return 1
  expect_short_err 1 && expect_err "^error: --output given twice \(\"o1\" and \"o2\"\)" || return 1
  expect_exit 1 "$EMC" in.xml --restart a/checkpoint.h5 --restart=b/checkpoint.h5 || return 1
  expect_short_err 1 && expect_err "^error: --restart given twice" || return 1
  [ ! -e o1 ] && [ ! -e o2 ] || { echo "an output directory was created"; return 1; }
  expect_exit 0 "$EMC" in.xml --set Output/progress=false --set Time/end=0.05 --set=Time/end=0.02 \
    --output o3 || return 1
  [ "$(grep -c . last.err)" = 1 ] &&
    expect_err "^warning: --set Time/end given twice \(\"Time/end=0\.05\", then \"Time/end=0\.02\"\): the last one applies" ||
    return 1
  [ "$(rst_last_step o3/monitors.csv 2>/dev/null || tail -1 o3/monitors.csv | cut -d, -f1)" = 2 ] ||
    { echo "the last --set did not apply"; return 1; }
}

# The summary's energy error of a body that starts nearly at rest and falls (E0 = 3e-6 J, K
# reaching 4 J): relative to the largest K + W + |Pi|, the scale of E's round-off, it is
# round-off (6e-13); relative to |E0| it read 1e-3, a false alarm. The number is the one
# recomputed from monitors.csv with that scale.
hostile_summary_energy_error_uses_the_energy_scale() {
  emc_good_input in.xml
  expect_exit 0 "$EMC" in.xml --set Output/progress=false --set "Loads/gravity={0,0,-9.81}" \
    --set "Bodies/block/Initial/velocity={0,1e-4,0}" --set Time/end=0.3 --output e || return 1
  local said
  said=$(sed -En 's/.*max \|E-E0\|\/max\(K\+W\+\|Pi\|\) = ([0-9.e+-]+);.*/\1/p' last.out)
  [ -n "$said" ] || { echo "no energy error in: $(head -1 last.out)"; return 1; }
  /usr/bin/python3 - "$said" e/monitors.csv <<'PY' || return 1
import csv, sys
said, rows = float(sys.argv[1]), list(csv.DictReader(open(sys.argv[2])))
E = [float(r['total']) + float(r['dissipated']) for r in rows]
scale, err = 0.0, 0.0
for r, e in zip(rows, E):
    scale = max(scale, float(r['kinetic']) + float(r['elastic']) + abs(float(r['potential'])))
    err = max(err, abs(e - E[0]) / scale)
if not (said < 1e-11 and abs(said - err) <= 1e-3 * err + 1e-300):
    sys.exit('summary %g, recomputed %g (|E0| = %g)' % (said, err, abs(E[0])))
PY
}

# A restarted run's summary counts the steps it computed, from the checkpoint's step, and its
# Newton iterations per step are theirs (it counted the steps before the checkpoint as its own:
# "200 steps, 1.88 Newton iterations/step" after computing 130 steps at 2.89).
hostile_restart_summary_counts_its_own_steps() {
  emc_contact_input in.xml
  expect_exit 0 "$EMC" in.xml --set Output/progress=false --set Time/end=0.06 \
    --set "Output/checkpoint every=4" --output r || return 1
  expect_exit 0 "$EMC" in.xml --set Output/progress=false --set Time/end=0.06 \
    --restart r/checkpoint.h5 || return 1
  grep -Eq "; 2 steps from step 4 to t = 0\.06 " last.out || { head -1 last.out; return 1; }
  local said mean
  said=$(sed -En 's/.*, ([0-9.]+) Newton iterations\/step\).*/\1/p' last.out)
  mean=$(awk -F, 'NR > 1 && $1 > 4 {s += $14; n++} END {printf "%.2f", s / n}' r/monitors.csv)
  [ "$said" = "$mean" ] || { echo "Newton iterations/step $said, the monitors' mean $mean"; return 1; }
}
