#!/usr/bin/env bash
# Formats the C++ of plugin/ (*.h, *.hpp, *.cpp) in place in the style of .clang-format
# (LAMMPS's), then lists the lines still longer than 100 columns, which clang-format leaves as
# they are (a long comment or string: shorten them by hand). tests/test_format.py checks both.
#   bash scripts/format.sh            format plugin/
#   bash scripts/format.sh --check    change nothing; list the files that differ (exit 1 if any)
# clang-format 14 (Debian 12's) or later: apt-get install clang-format (scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."

CLANG_FORMAT="${CLANG_FORMAT:-clang-format}"
if ! command -v "$CLANG_FORMAT" >/dev/null; then
  echo "format: $CLANG_FORMAT not found (apt-get install clang-format)" >&2
  exit 2
fi
mapfile -d '' files < <(find plugin -type f \( -name '*.h' -o -name '*.hpp' -o -name '*.cpp' \) \
  -print0 | sort -z)

status=0
if [ "${1:-}" = "--check" ]; then
  for f in "${files[@]}"; do
    if ! "$CLANG_FORMAT" --style=file --dry-run -Werror "$f" >/dev/null 2>&1; then
      echo "format: $f differs from .clang-format's style"
      status=1
    fi
  done
else
  "$CLANG_FORMAT" --style=file -i "${files[@]}"
  echo "format: ${#files[@]} files of plugin/ formatted"
fi
# characters, not bytes (a comment's § is one column), as clang-format counts them
if LC_ALL=C.UTF-8 grep -a -n -E '^.{101,}' "${files[@]}" | sed 's/^/format: longer than 100 columns: /' \
    | cut -c1-160 | grep -a .; then
  status=1
fi
exit $status
