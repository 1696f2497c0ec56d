#!/usr/bin/env bash
# clang-format (.clang-format) over every C and C++ file git tracks.
#   scripts/format.sh           rewrites the files in place
#   scripts/format.sh --check   changes nothing; lists each file clang-format would change and
#                               exits 1 if there is one (CI runs this)
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-}
if [[ -n "$mode" && "$mode" != "--check" ]]; then
  echo "format.sh: unknown option '$mode' (only --check)" >&2
  exit 2
fi
mapfile -t files < <(git ls-files '*.c' '*.cc' '*.cpp' '*.h' '*.hpp')
if [[ -z "$mode" ]]; then
  printf '%s\0' "${files[@]}" | xargs -0 -n 64 -P "$(nproc)" clang-format -i
  echo "format.sh: formatted ${#files[@]} files"
  exit 0
fi
# Each file clang-format would change is named in its "code should be clang-formatted" errors.
mapfile -t unformatted < <(printf '%s\0' "${files[@]}" |
  xargs -0 -n 64 -P "$(nproc)" clang-format --dry-run -Werror 2>&1 |
  sed -n 's/^\(.*\):[0-9]*:[0-9]*: error: code should be clang-formatted.*/\1/p' | sort -u)
if [[ ${#unformatted[@]} -gt 0 ]]; then
  echo "format.sh: clang-format would change ${#unformatted[@]} of ${#files[@]} files:" >&2
  printf '  %s\n' "${unformatted[@]}" >&2
  echo "format.sh: run scripts/format.sh (or make format) and commit the result" >&2
  exit 1
fi
echo "format.sh: all ${#files[@]} files formatted"
