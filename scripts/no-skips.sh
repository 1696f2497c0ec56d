#!/usr/bin/env bash
# Fails when the last ctest run in BUILD_DIR skipped a test (GTEST_SKIP or a skip return code):
# CI runs it after each test pass, on a machine that install-deps.sh made able to run them all,
# so that a test cannot pass by not running.
#   scripts/no-skips.sh BUILD_DIR
set -euo pipefail
build_dir=${1:?usage: scripts/no-skips.sh BUILD_DIR}
log="$build_dir/Testing/Temporary/LastTest.log"
if [[ ! -f "$log" ]]; then
  echo "no-skips: $log: no ctest log (run the tests first)" >&2
  exit 2
fi
# ctest writes each test's output between "<n>/<m> Test: NAME" and its end; a skipped one shows
# gtest's "[  SKIPPED ]" line or ctest's "Test Skipped".
mapfile -t skipped < <(awk '/^[0-9]+\/[0-9]+ Test: /{name=$3} /\[  SKIPPED \] [^ ]|Test Skipped/{print name}' "$log" | sort -u)
if [[ ${#skipped[@]} -gt 0 ]]; then
  echo "no-skips: ${#skipped[@]} tests were skipped on a machine meant to run them all:" >&2
  printf '  %s\n' "${skipped[@]}" >&2
  grep -h -A2 '\[  SKIPPED \] [^ ]' "$log" | head -20 >&2 || true
  exit 1
fi
echo "no-skips: no test was skipped ($log)"
