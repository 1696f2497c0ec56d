#!/usr/bin/env bash
# The mutation benchmark of docs/FILE_FORMAT.md: 10,000 damaged copies of a fur
# recording and of its label store (with an operator's edits), read under a time
# limit; with a build made with -DTACTILE_SANITIZE=address,undefined the table
# counts what the sanitizers find as crashes.
#   bench/mutation_bench.sh BUILD_DIR [COPIES]
set -euo pipefail
build=${1:?usage: bench/mutation_bench.sh BUILD_DIR [COPIES]}
copies=${2:-10000}
work=$(mktemp -d /tmp/tactile-mutation-XXXXXX)
trap 'rm -rf "$work"' EXIT
# The recording is written by the build under test; the same seed, the same bytes.
"$build/bin/tactile" simulate --skin fur --subjects 1 --repetitions 2 --seed 7 --out "$work/ws" > /dev/null
recording=$(ls "$work"/ws/*.h5 | head -1)
cp "$work/ws/labels.db" "$work/labels.db"
cp "$recording" "$work/recording.h5"
ls -l "$work/recording.h5" "$work/labels.db" >&2
# A sanitizer report ends the child with an abort: counted as a crash.
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:abort_on_error=1:print_stacktrace=1}
"$build/bench/mutation_bench" --recording "$work/recording.h5" --labels "$work/labels.db" \
  --edit-labels --copies "$copies" --timeout 30 --work "$work/copies"
