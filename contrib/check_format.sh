#!/bin/bash
# Fails, listing them, when C++ files (*.cc, *.h) of source/, include/ or tests/
# are not formatted as clang-format 14 formats them with the repository's
# .clang-format (Debian 12 package clang-format). Other versions format some
# constructs differently, so version 14 is required.
set -euo pipefail
cd "$(dirname "$0")/.."
clang_format=clang-format-14
if ! command -v "$clang_format" >/dev/null; then
  echo "check_format.sh: $clang_format not found; install the Debian package clang-format" \
       "(bash contrib/install_dependencies.sh clang-format)." >&2
  exit 1
fi
unformatted=()
while IFS= read -r -d '' file; do
  "$clang_format" --dry-run --Werror --style=file "$file" >/dev/null 2>&1 || unformatted+=("$file")
done < <(find source include tests -type f \( -name '*.cc' -o -name '*.h' \) -print0 | sort -z)
if [ ${#unformatted[@]} -gt 0 ]; then
  echo "check_format.sh: ${#unformatted[@]} file(s) not formatted by $clang_format with .clang-format:" >&2
  printf '  %s\n' "${unformatted[@]}" >&2
  echo "Format them with: $clang_format -i <file>..." >&2
  exit 1
fi
echo "check_format.sh: all C++ files of source/, include/, tests/ are formatted ($clang_format)."
