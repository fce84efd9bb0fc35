#!/usr/bin/env bash
# Fails (exit 1) if a tracked C++ file differs from .clang-format under Debian's clang-format,
# listing them (`bash scripts/check_format.sh --fix` formats them in place), or if a tracked
# Markdown file has a prose line over 120 characters (fenced code and table rows are exempt: a
# table row cannot be wrapped). Run by ctest (`format`).
set -euo pipefail
cd "$(dirname "$0")/.."
CF=${CLANG_FORMAT:-clang-format}
command -v "$CF" >/dev/null || { echo "check_format: $CF not found (apt-get install clang-format)" >&2; exit 2; }
# Markdown prose: at most 120 characters a line (docs/developer-guide.md, "Style")
mapfile -t docs < <(git ls-files '*.md' 2>/dev/null || find . -name '*.md' -not -path './build*')
long=$(awk 'FNR == 1 { code = 0 } /^ *```/ { code = !code; next }
            !code && !/^ *\|/ && length > 120 { printf "  %s:%d: %d characters\n", FILENAME, FNR, length }' \
  "${docs[@]}")
if [ -n "$long" ]; then
  echo "check_format: Markdown lines over 120 characters (wrap them):" >&2
  echo "$long" >&2
  exit 1
fi
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
