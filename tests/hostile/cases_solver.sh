# Newton, the linear solver, signals and the ranks' agreement on the input: runs that must stop
# when asked (SIGTERM, SIGINT, SIGHUP, also inside a long Krylov solve and during setup),
# solver counts and tolerances that cannot work, and ranks started with different inputs.
# No case asserts a duration: each waits for a line or a file, and its timeout is a safety net.

# wait_for_line FILE REGEX [SECONDS]: until FILE has a line matching REGEX (a safety timeout of
# SECONDS, default 60, on a quiet machine).
wait_for_line() {
  for _ in $(seq $(($(safety "${3:-60}") * 10))); do
    grep -Eq -- "$2" "$1" 2>/dev/null && return 0
    sleep 0.1
  done
  echo "no line /$2/ in $1"
  return 1
}

# wait_caught PID SIGNAL_NUMBER: until PID has a handler for the signal (safety 30 s).
wait_caught() {
  for _ in $(seq $(($(safety 30) * 10))); do
    local mask
    mask=$(awk '/^SigCgt:/ { print $2 }' "/proc/$1/status" 2>/dev/null) || return 1
    [ -n "$mask" ] && [ $((16#$mask >> ($2 - 1) & 1)) -ne 0 ] && return 0
    sleep 0.1
  done
  return 1
}

# stop_and_wait PID SIGNAL: sends SIGNAL and waits for PID (its exit code in STOP_RC), with a
# safety net (120 s quiet, then SIGKILL).
stop_and_wait() {
  kill "-$2" "$1"
  local secs
  secs=$(safety 120)
  for _ in $(seq $((secs * 10))); do
    kill -0 "$1" 2>/dev/null || break
    sleep 0.1
  done
  kill -KILL "$1" 2>/dev/null && echo "still running $secs s after SIG$2"
  STOP_RC=0
  wait "$1" || STOP_RC=$?
}

# SIGINT and SIGHUP reach the run only if the shell did not start it with them ignored (a
# background job of a non-interactive shell ignores SIGINT; emcontact keeps an ignored signal
# ignored, as nohup expects): start it with their default actions.
run_bg() {
  env --default-signal=SIGINT,SIGHUP "$EMC" "$@" >last.out 2>last.err &
}

# --- a signal within a long step, and inside one long Krylov solve ---

hostile_sigterm_within_a_long_step_stops() {
  emc_good_input in.xml
  # every linear solve fails its residual check after 3000 iterations: the first step takes
  # minutes of retries (20 cuts); Newton's trace line of the first failed solve says that the
  # time loop runs
  EMC_NEWTON_TRACE=1 run_bg in.xml --set "Bodies/block/Initial/velocity={1,0,0}" \
    --set "Bodies/block/Initial/angular velocity={0,0,5}" --set Bodies/block/Mesh/size=0.01 \
    --set "Solver/Linear/tolerance=1e-300" --set "Solver/Linear/max iterations=3000" \
    --set "Time/max step cuts=20" --set Solver/Linear/preconditioner=none --output out
  local pid=$!
  wait_for_line last.err '^newton failed'
  stop_and_wait $pid TERM
  [ "$STOP_RC" -eq 1 ] || { echo "exit $STOP_RC, expected 1"; cat last.err; return 1; }
  expect_err "stopped by SIGTERM after step 0"
  test -s out/checkpoint.h5
}

hostile_sigterm_inside_a_long_krylov_solve_stops() {
  emc_good_input in.xml
  # one GMRES solve without preconditioner on a nearly incompressible block: up to 100000
  # iterations (minutes). Belos' status output every 100 iterations shows the solve running
  # (the solve that checks the Belos parameters at setup converges in a few).
  run_bg in.xml --set Bodies/block/Mesh/size=0.01 --set Bodies/block/Material/poisson=0.49999 \
    --set "Bodies/block/Initial/velocity={1,0,0}" --set "Bodies/block/Initial/angular velocity={0,0,5}" \
    --set "Solver/Linear/max iterations=100000" --set Solver/Linear/preconditioner=none \
    --set Solver/Linear/Belos/Verbosity=32 --set "Solver/Linear/Belos/Output Frequency=100" \
    --output out
  local pid=$!
  wait_for_line last.out 'Number of Iterations = [0-9]{3,} <'
  stop_and_wait $pid TERM
  [ "$STOP_RC" -eq 1 ] || { echo "exit $STOP_RC, expected 1"; tail -3 last.err; return 1; }
  expect_err "^error: stopped by SIGTERM after step 0 .*--restart out/checkpoint.h5"
  expect_short_err 1
  test -s out/checkpoint.h5
}

# --- SIGINT and SIGHUP as SIGTERM: during setup and during the run ---

signal_during_setup() {
  emc_good_input in.xml
  # a mesh that takes many seconds to generate
  run_bg in.xml --set Bodies/block/Mesh/size=0.003 --output out
  local pid=$!
  wait_caught $pid "$2" || { echo "no handler for SIG$1 within 30 s"; kill -KILL $pid; return 1; }
  stop_and_wait $pid "$1"
  [ "$STOP_RC" -eq 1 ] || { echo "exit $STOP_RC, expected 1"; cat last.err; return 1; }
  expect_err "^error: stopped by SIG$1 during setup"
  expect_short_err 1
}

hostile_sigint_during_setup_says_so() {
  signal_during_setup INT 2
}

hostile_sighup_during_setup_says_so() {
  signal_during_setup HUP 1
}

signal_during_run() {
  emc_good_input in.xml
  local opts=(--set Time/end=2 --set Bodies/block/Mesh/size=0.02 --set "Output/checkpoint every=4"
    --set Output/progress=false
    --set "Bodies/block/Initial/angular velocity={0,0,5}")
  run_bg in.xml "${opts[@]}" --output out
  local pid=$!
  for _ in $(seq $(($(safety 60) * 10))); do
    [ -f out/monitors.csv ] && [ "$(wc -l <out/monitors.csv)" -ge 6 ] && break
    sleep 0.1
  done
  stop_and_wait $pid "$1"
  [ "$STOP_RC" -eq 1 ] || { echo "exit $STOP_RC, expected 1"; cat last.err; return 1; }
  expect_err "^error: stopped by SIG$1 after step [0-9]+ .*continue with --restart out/checkpoint.h5"
  expect_short_err 1
  # the monitors of every accepted step, and the hint's restart runs to the end
  local last
  last=$(tail -1 out/monitors.csv | cut -d, -f1)
  [ "$last" -ge 4 ] || { echo "monitors end at step $last"; return 1; }
  expect_exit 0 "$EMC" in.xml "${opts[@]}" --output out --restart out/checkpoint.h5
  [ "$(tail -1 out/monitors.csv | cut -d, -f1)" -eq 200 ]
}

hostile_sigint_during_run_checkpoints() {
  signal_during_run INT
}

hostile_sighup_during_run_checkpoints() {
  signal_during_run HUP
}

# --- counts that make one solve, setup or preconditioner application endless ---

hostile_absurd_linear_solver_counts_refused() {
  emc_good_input in.xml
  local bad
  for bad in "Solver/Linear/max iterations=2000000000" \
    "Solver/Linear/Belos/Maximum Iterations=2000000000" \
    "Solver/Linear/Ifpack2/chebyshev: degree=2000000000" \
    "Solver/Linear/MueLu/max levels=1000000" \
    "Solver/Linear/MueLu/smoother: params/chebyshev: degree=1000000"; do
    local extra=()
    case "$bad" in
      *Ifpack2*) extra=(--set Solver/Linear/preconditioner=chebyshev) ;;
      *MueLu*) extra=(--set Solver/Linear/preconditioner=muelu) ;;
    esac
    expect_exit_within 60 1 "$EMC" in.xml --set "$bad" "${extra[@]}" --output out
    expect_err "\"${bad%%=*}[\"=].*allowed: an int(eger)? (from 1 to|up to) "
    expect_short_err 1
    [ ! -e out ] || { echo "$bad: out/ written"; return 1; }
  done
}

# --- tolerances and inertia that make Newton accept the start iterate ---

hostile_newton_absolute_tolerance_above_residual_refused() {
  cp "$HERE/../../inputs/tumbling_box.xml" in.xml
  expect_exit_within 60 1 "$EMC" in.xml --set Time/end=0.05 \
    --set "Solver/Newton/absolute tolerance=1e300" --output out
  expect_err 'parameter "Solver/Newton/absolute tolerance": 1e\+300 is not below'
  expect_short_err 1
  [ ! -e out ] || { echo "out/ written"; return 1; }
}

hostile_density_below_roundoff_refused() {
  cp "$HERE/../../inputs/tumbling_box.xml" in.xml
  # within the density's physical bounds, but with the stiffest young its bounds allow
  expect_exit_within 60 1 "$EMC" in.xml --set Time/end=0.05 \
    --set Bodies/box/Material/density=1e-12 --set Bodies/box/Material/young=1e14 --output out
  expect_err 'parameter "Bodies/box/Material/density": .* below the round-off of its stiffness'
  expect_short_err 1
  [ ! -e out ] || { echo "out/ written"; return 1; }
  local rho
  for rho in 1e-300 4.9e-324; do  # below the physical bounds
    expect_exit_within 60 1 "$EMC" in.xml --set Time/end=0.05 \
      --set Bodies/box/Material/density=$rho --output out
    expect_err '"Bodies/box/Material/density=.*": value .* is out of range'
    expect_short_err 1
    [ ! -e out ] || { echo "density $rho: out/ written"; return 1; }
  done
}

# An absolute tolerance that the start iterate (the last step's increment, after the first
# step) meets: it is accepted only at round-off, so every step takes a Newton iteration (the
# predictor accepted as it was gave E 57% off in 50 steps).
hostile_newton_absolute_tolerance_does_not_accept_the_predictor() {
  cp "$HERE/../../inputs/tumbling_box.xml" in.xml
  expect_exit 0 "$EMC" in.xml --set Time/end=0.5 --set "Solver/Newton/absolute tolerance=1e3" \
    --set Output/every=0 --output out
  /usr/bin/python3 - <<'PY'
import csv
rows = list(csv.DictReader(open("out/monitors.csv")))
its = [int(r["newton_iterations"]) for r in rows[1:]]
assert min(its) >= 1, its
lx = [float(r["Lx"]) for r in rows]
assert all(abs(v - lx[0]) < 1e-2 * abs(lx[0]) for v in lx), lx  # no flip
PY
}

# --- ranks started with different inputs run rank 0's ---

hostile_mpmd_other_arguments_run_rank0s() {
  emc_good_input in.xml
  local opts=(in.xml --set Time/end=0.05 --set "Bodies/block/Initial/velocity={1,0,0}")
  expect_exit_within 120 0 "${MPIRUN[@]}" -np 2 "$EMC" "${opts[@]}" --output same
  local other
  for other in Output/every=1 Time/dt=0.005 Solver/Linear/type=mumps; do
    rm -rf mp
    expect_exit_within 120 0 "${MPIRUN[@]}" -np 1 "$EMC" "${opts[@]}" --output mp : \
      -np 1 "$EMC" "${opts[@]}" --set "$other" --output mp
    expect_err "^warning: rank 1 was started with other arguments than rank 0; every rank runs"
    cmp same/monitors.csv mp/monitors.csv
  done
}

hostile_mpmd_other_input_files_run_rank0s() {
  mkdir r0 r1
  emc_good_input r0/in.xml
  sed 's/name="end" type="double" value="0.02"/name="end" type="double" value="0.05"/' \
    r0/in.xml >r1/in.xml
  cmp -s r0/in.xml r1/in.xml && { echo "r1/in.xml not changed"; return 1; }
  # the same command line, in directories whose in.xml differ (per-node copies of a file)
  expect_exit_within 120 0 "${MPIRUN[@]}" -np 1 -wdir "$PWD/r0" "$EMC" in.xml --output "$PWD/mp" : \
    -np 1 -wdir "$PWD/r1" "$EMC" in.xml --output "$PWD/mp"
  expect_exit_within 120 0 "${MPIRUN[@]}" -np 2 -wdir "$PWD/r0" "$EMC" in.xml --output "$PWD/same"
  cmp same/monitors.csv mp/monitors.csv
}

# A one-rank direct solver on 3 ranks is refused listing every solver that runs there (klu2's
# refusal left out mumps, which runs on any rank count); the one it lists does run.
hostile_one_rank_solver_lists_what_runs_on_three_ranks() {
  emc_good_input in.xml
  local t
  for t in klu2 umfpack; do
    expect_exit 1 "${MPIRUN[@]}" -np 3 "$EMC" in.xml --set "Solver/Linear/type=$t" --output o || return 1
    expect_err "type = $t runs on one rank only .*allowed on 3 ranks: gmres, cg, mumps" || return 1
  done
  expect_exit 0 "${MPIRUN[@]}" -np 3 "$EMC" in.xml --set Output/progress=false \
    --set Solver/Linear/type=mumps --output o || return 1
}
