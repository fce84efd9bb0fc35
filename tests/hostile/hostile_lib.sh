# Helpers for the hostile cases (sourced by run_hostile.sh).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
MPIRUN=(mpiexec --allow-run-as-root --oversubscribe --mca mpi_yield_when_idle 1)

# emc_good_input FILE: writes a valid minimal input (one small box, two steps) to FILE.
emc_good_input() {
  cp "$HERE/good_box.xml" "$1"
}

# expect_exit CODE CMD...: runs CMD (output to ./last.out and ./last.err) under a 120 s
# timeout; fails unless it exits with CODE.
expect_exit() {
  local want=$1
  shift
  local rc=0
  timeout -k 5 120 "$@" >last.out 2>last.err || rc=$?
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

# expect_exit_within SECONDS CODE CMD...: expect_exit with a shorter timeout (a hang shows as
# exit 124 quickly).
expect_exit_within() {
  local secs=$1 want=$2
  shift 2
  local rc=0
  timeout -k 5 "$secs" "$@" >last.out 2>last.err || rc=$?
  if [ "$rc" -ne "$want" ]; then
    echo "expected exit $want, got $rc (timeout ${secs} s) from: $*"
    tail -n 20 last.out last.err
    return 1
  fi
}
