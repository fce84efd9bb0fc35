#!/usr/bin/env bash
# clang-tidy with the project's .clang-tidy over src/ (or the files given, or the files changed
# since a base commit), from a build tree's compile_commands.json; exit 1 if any check fires.
#   bash scripts/run_clang_tidy.sh [BUILD_DIR] [FILE ...]      (default build, every src/ file)
#   bash scripts/run_clang_tidy.sh --changed [BASE] [BUILD_DIR]
#       the src/ files changed between BASE and HEAD, and the src/ files that include a changed
#       public header (include/emcontact/, kernels/). BASE defaults to the merge base with
#       origin/main when HEAD is not on it, else HEAD's first parent (the last commit, or what a
#       merge brought in). Without a base (a one-commit or shallow clone) it says so and checks
#       nothing: run the first form for every file.
# Environment: EMC_JOBS (parallel runs, default nproc), CLANG_TIDY (default clang-tidy).
set -euo pipefail
cd "$(dirname "$0")/.."
CT=${CLANG_TIDY:-clang-tidy}

changed_files() {  # BASE: the src/*.cpp to check, one a line
  local base=$1 f
  local -a headers=()
  while IFS= read -r f; do
    [ -f "$f" ] || continue  # deleted
    case $f in
      src/*.cpp) echo "$f" ;;
      include/emcontact/*.hpp) headers+=("${f#include/}") ;;
      kernels/*.hpp) headers+=("$f") ;;
      src/*.hpp) headers+=("${f##*/}") ;;  # a module's private header, included by its name
    esac
  done < <(git diff --name-only "$base" HEAD)
  for f in "${headers[@]}"; do
    git grep -l -F "#include \"$f\"" -- 'src/*.cpp' || true
  done
}

if [ "${1:-}" = "--changed" ]; then
  shift
  base=${1:-}
  [ $# -gt 0 ] && shift
  BUILD=${1:-build}
  if [ -z "$base" ]; then
    if git rev-parse -q --verify origin/main >/dev/null &&
      ! git merge-base --is-ancestor HEAD origin/main; then
      base=$(git merge-base HEAD origin/main)
    elif git rev-parse -q --verify 'HEAD^' >/dev/null; then
      base='HEAD^'
    else
      echo "run_clang_tidy: no base commit to compare HEAD with (a one-commit or shallow clone):" \
        "nothing checked; 'bash scripts/run_clang_tidy.sh $BUILD' checks every src/ file"
      exit 0
    fi
  fi
  mapfile -t files < <(changed_files "$base" | sort -u)
  if [ ${#files[@]} -eq 0 ]; then
    echo "run_clang_tidy: no src/ file changed since $(git rev-parse --short "$base"), none" \
      "includes a changed public header: nothing to check"
    exit 0
  fi
  echo "run_clang_tidy: ${#files[@]} files changed since $(git rev-parse --short "$base")"
else
  BUILD=${1:-build}
  shift || true
  if [ $# -gt 0 ]; then files=("$@"); else mapfile -t files < <(git ls-files 'src/*.cpp'); fi
fi
[ -f "$BUILD/compile_commands.json" ] || { echo "run_clang_tidy: no $BUILD/compile_commands.json (configure first)" >&2; exit 2; }
log=$(mktemp)
trap 'rm -f "$log"' EXIT
printf '%s\n' "${files[@]}" | xargs -P "${EMC_JOBS:-$(nproc)}" -n 1 "$CT" -p "$BUILD" --quiet 2>/dev/null >"$log" || true
if grep -qE "(warning|error):" "$log"; then
  grep -E -A3 "(warning|error):" "$log" >&2
  echo "run_clang_tidy: $(grep -cE '(warning|error):' "$log") findings in ${#files[@]} files" >&2
  exit 1
fi
echo "run_clang_tidy: ${#files[@]} files clean"
