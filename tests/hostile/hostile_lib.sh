# Helpers for the hostile cases (sourced by run_hostile.sh).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
MPIRUN=(mpiexec --allow-run-as-root --oversubscribe --mca mpi_yield_when_idle 1 --bind-to none)

# safety SECONDS: a safety timeout of SECONDS on a quiet machine, scaled for a loaded one
# (EMC_TIMEOUT_SCALE, default 4: oversubscribed MPI ranks beside other CPU-bound processes run
# 3-5 times slower) and kept under the ctest TIMEOUT (300 s) so that the case reports what hung.
# A timeout is a net against hangs, never a duration asserted: a passing case never waits it.
safety() {
  local s=$(($1 * ${EMC_TIMEOUT_SCALE:-4}))
  [ "$s" -gt 270 ] && s=270
  echo "$s"
}

# emc_good_input FILE: writes a valid minimal input (one small box, two steps) to FILE.
emc_good_input() {
  cp "$HERE/good_box.xml" "$1"
}

# expect_exit CODE CMD...: runs CMD (output to ./last.out and ./last.err) under a safety timeout
# (120 s quiet); fails unless it exits with CODE.
expect_exit() {
  local want=$1
  shift
  local rc=0
  timeout -k 5 "$(safety 120)" "$@" >last.out 2>last.err || rc=$?
  if [ "$rc" -ne "$want" ]; then
    echo "expected exit $want, got $rc from: $*"
    tail -n 20 last.out last.err
    return 1
  fi
}

# expect_err REGEX: the last command's stderr matches REGEX (grep -E).
expect_err() {
  if ! grep -Eq -- "$1" last.err; then
    echo "stderr does not match /$1/:"
    head -20 last.err
    return 1
  fi
}

# expect_short_err N: the last command's stderr has at most N lines (a clear message, no dump).
expect_short_err() {
  local n
  n=$(wc -l <last.err)
  if [ "$n" -gt "$1" ]; then
    echo "stderr has $n lines (at most $1 allowed):"
    head -40 last.err
    return 1
  fi
}

# expect_exit_within SECONDS CODE CMD...: expect_exit with a shorter safety timeout (SECONDS on
# a quiet machine: a hang shows as exit 124 sooner).
expect_exit_within() {
  local secs want=$2
  secs=$(safety "$1")
  shift 2
  local rc=0
  timeout -k 5 "$secs" "$@" >last.out 2>last.err || rc=$?
  if [ "$rc" -ne "$want" ]; then
    echo "expected exit $want, got $rc (timeout ${secs} s) from: $*"
    tail -n 20 last.out last.err
    return 1
  fi
}
