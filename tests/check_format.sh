#!/usr/bin/env bash
# SourcesAreClangFormatted: every tracked C++ source and header matches the
# repository's .clang-format (clang-format 14, Debian 12), so style never
# needs a review comment. Prints the files that differ.
set -euo pipefail
cd "$1"
mapfile -t files < <(git ls-files '*.cpp' '*.h')
if ((${#files[@]} == 0)); then
  echo "no C++ sources found under $1"
  exit 1
fi
if ! clang-format --dry-run --Werror "${files[@]}" 2>/tmp/quadra-format.$$; then
  grep -E ': (warning|error):' /tmp/quadra-format.$$ | cut -d: -f1 | sort -u |
    sed 's/^/not clang-formatted: /'
  rm -f /tmp/quadra-format.$$
  exit 1
fi
rm -f /tmp/quadra-format.$$
echo "${#files[@]} files clang-formatted"
