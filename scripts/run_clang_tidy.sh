#!/usr/bin/env bash
# clang-tidy with the project's .clang-tidy over src/ (or the files given), from a build tree's
# compile_commands.json; exit 1 if any check fires.
#   bash scripts/run_clang_tidy.sh [BUILD_DIR] [FILE ...]      (default build, every src/ file)
# Environment: EMC_JOBS (parallel runs, default nproc), CLANG_TIDY (default clang-tidy).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
shift || true
CT=${CLANG_TIDY:-clang-tidy}
[ -f "$BUILD/compile_commands.json" ] || { echo "run_clang_tidy: no $BUILD/compile_commands.json (configure first)" >&2; exit 2; }
if [ $# -gt 0 ]; then files=("$@"); else mapfile -t files < <(git ls-files 'src/*.cpp'); fi
log=$(mktemp)
trap 'rm -f "$log"' EXIT
printf '%s\n' "${files[@]}" | xargs -P "${EMC_JOBS:-$(nproc)}" -n 1 "$CT" -p "$BUILD" --quiet 2>/dev/null >"$log" || true
if grep -qE "(warning|error):" "$log"; then
  grep -E -A3 "(warning|error):" "$log" >&2
  echo "run_clang_tidy: $(grep -cE '(warning|error):' "$log") findings in ${#files[@]} files" >&2
  exit 1
fi
echo "run_clang_tidy: ${#files[@]} files clean"
