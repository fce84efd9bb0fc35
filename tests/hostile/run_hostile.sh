#!/usr/bin/env bash
# Re-runs the hostile and careless uses against the emcontact binary and prints how
# many are handled. Each case is a bash function `hostile_<name>` in one of the cases_*.sh files
# beside this script; it runs in a fresh, empty working directory (its own subshell) and returns
# 0 when the binary handles the case as promised (docs/user-guide.md, "What is refused").
#
#   tests/hostile/run_hostile.sh BUILD_DIR [name ...]     (default: every case)
#
# The helpers the cases may use (see hostile_lib.sh): $EMC (the binary), $MPIRUN (mpiexec with
# the root flags), $HERE (this directory), emc_good_input FILE, expect_exit, ...
set -uo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
BUILD="$(cd "${1:?usage: run_hostile.sh BUILD_DIR [name ...]}" && pwd)"
shift
export HERE BUILD
export EMC="$BUILD/bin/emcontact"
# shellcheck source=hostile_lib.sh
source "$HERE/hostile_lib.sh"
for f in "$HERE"/cases_*.sh; do
  # shellcheck disable=SC1090
  source "$f"
done
if [ $# -eq 0 ]; then
  mapfile -t names < <(declare -F | awk '{print $3}' | sed -n 's/^hostile_//p' | sort)
else
  names=("$@")
fi
pass=0
fail=0
for name in "${names[@]}"; do
  if ! declare -F "hostile_$name" >/dev/null; then
    echo "FAIL $name (no such case)"
    fail=$((fail + 1))
    continue
  fi
  dir="$(mktemp -d /tmp/emc_hostile.XXXXXX)"
  log="$dir.log"
  # not in an `if`: there bash ignores set -e inside the case, and a failed check in the middle
  # of a case would pass unnoticed (only its last command would count); nor in a || list
  (cd "$dir" && set -e && "hostile_$name") >"$log" 2>&1
  rc=$?
  if [ "$rc" -eq 0 ]; then
    echo "ok   $name"
    pass=$((pass + 1))
    rm -rf "$dir" "$log"
  else
    echo "FAIL $name (work dir $dir)"
    sed 's/^/     | /' "$log" | tail -40
    fail=$((fail + 1))
  fi
done
echo "hostile: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
