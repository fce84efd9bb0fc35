#!/usr/bin/env bash
# Fails (exit 1) if a tracked C++ file differs from .clang-format under Debian's clang-format,
# listing them; `bash scripts/check_format.sh --fix` formats them in place. Run by ctest (`format`).
set -euo pipefail
cd "$(dirname "$0")/.."
CF=${CLANG_FORMAT:-clang-format}
command -v "$CF" >/dev/null || { echo "check_format: $CF not found (apt-get install clang-format)" >&2; exit 2; }
mapfile -t files < <(git ls-files '*.cpp' '*.hpp' '*.h' 2>/dev/null || find src include kernels tests perf -name '*.[ch]pp')
if [ "${1:-}" = "--fix" ]; then
  "$CF" -i "${files[@]}"
  exit 0
fi
# One clang-format process for every file (a process per file costs 30 times the CPU); the
# files that differ are those its -Werror diagnostics name.
log=$(mktemp)
trap 'rm -f "$log"' EXIT
if ! "$CF" --dry-run -Werror "${files[@]}" >/dev/null 2>"$log"; then
  mapfile -t bad < <(sed -n 's/^\([^:]*\):[0-9]*:[0-9]*: error:.*/\1/p' "$log" | sort -u)
  if [ ${#bad[@]} -eq 0 ]; then
    cat "$log" >&2
    echo "check_format: $CF failed" >&2
    exit 1
  fi
  echo "check_format: ${#bad[@]} of ${#files[@]} files differ from .clang-format ($("$CF" --version)):" >&2
  printf '  %s\n' "${bad[@]}" >&2
  echo "fix with: bash scripts/check_format.sh --fix" >&2
  exit 1
fi
echo "check_format: ${#files[@]} files formatted"
