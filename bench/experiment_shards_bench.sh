#!/bin/sh
# `tactile experiment --repeats R` in one process against the same repeats as N shards run
# side by side and merged (issue 29): wall times, their ratio, and a cmp of the two --out
# documents (they must be the same bytes). The ratio is bounded by the machine's cores.
# Usage: bench/experiment_shards_bench.sh [BUILD_DIR] [EXPERIMENT] [REPEATS] [SHARDS] [--quick]
set -eu
BUILD=${1:-build}
NAME=${2:-fur-ml}
REPEATS=${3:-4}
SHARDS=${4:-2}
QUICK=${5:-}
TACTILE="$BUILD/bin/tactile"
WORK=$(mktemp -d /tmp/experiment-shards-bench.XXXXXX)
trap 'rm -rf "$WORK"' EXIT

now() { date +%s.%N; }

start=$(now)
"$TACTILE" experiment "$NAME" $QUICK --repeats "$REPEATS" --out "$WORK/one.json" >/dev/null 2>&1
one=$(echo "$(now) - $start" | bc)

start=$(now)
i=1
while [ "$i" -le "$SHARDS" ]; do
  "$TACTILE" experiment "$NAME" $QUICK --repeats "$REPEATS" --out "$WORK/merged.json" \
    --shard "$i/$SHARDS" >/dev/null 2>&1 &
  i=$((i + 1))
done
wait
"$TACTILE" merge "$WORK"/merged.json.part-* >/dev/null
sharded=$(echo "$(now) - $start" | bc)

same=no
cmp -s "$WORK/one.json" "$WORK/merged.json" && same=yes
echo "| experiment | repeats | one process | $SHARDS shards side by side + merge | ratio | same bytes |"
echo "|---|---|---|---|---|---|"
printf '| %s%s | %s | %.1f s | %.1f s | %.2f | %s |\n' "$NAME" "${QUICK:+ $QUICK}" "$REPEATS" \
  "$one" "$sharded" "$(echo "$one / $sharded" | bc -l)" "$same"
