#!/bin/sh
# The grid pipeline against generic's per-taxel columns on simulated pressure grids (issue 26):
# simulate grid:16x16 and grid:19x27 (5 subjects, 10 touches per gesture each), extract
# `grid`, `generic` with per_channel=yes (its per-taxel block) and `generic` as it chooses
# (per_channel=auto: whole-grid columns above 64 channels), evaluate leave one subject out.
# Writes bench/compare/GRID.md. Usage: bench/grid_bench.sh [BUILD_DIR] [SEED]
# EVALUATOR=path/to/tactile evaluates the tables with another build's `tactile evaluate`
# (one that has the tree ensembles before their branch is merged).
set -eu
BUILD=${1:-build}
SEED=${2:-1}
TACTILE="$BUILD/bin/tactile"
EVALUATOR=${EVALUATOR:-$TACTILE}
WORK=$(mktemp -d /tmp/grid-bench.XXXXXX)
OUT=bench/compare/GRID.md
CLASSIFIERS="medium-tree tree linear-svm"
# Ensembles, when this build has them (another branch of issue 26 brings them).
for name in random-forest bagged-trees; do
  if "$EVALUATOR" evaluate --list | grep -q "^$name "; then CLASSIFIERS="$CLASSIFIERS $name"; fi
done

accuracy() {  # features.csv classifier -> "81.4"
  "$EVALUATOR" evaluate --features "$1" --classifier "$2" --protocol loso --seed "$SEED" --threads 1 |
    awk '/^accuracy/ { gsub(/[(]/, "", $0); print $(NF-1) }'
}

{
  echo "# Whole-grid features against per-taxel columns (simulated pressure grids)"
  echo
  echo "Made by \`bench/grid_bench.sh\` (seed $SEED) on $(date -u +%Y-%m-%d); accuracy over"
  echo "every touch, leave one subject out (5 subjects, 7 gestures x 10 each; each of a pat's 1-3"
  echo "pats is its own touch, so 70-90 touches a subject)."
  if [ "$EVALUATOR" != "$TACTILE" ]; then
    echo "Tables evaluated by \`$EVALUATOR\` (git $(git -C "$(dirname "$EVALUATOR")/../.." log -1 --format=%h 2>/dev/null || echo '?'))."
  fi
  echo
  echo "| grid | pipeline | columns | classifier | accuracy |"
  echo "|---|---|---|---|---|"
} > "$OUT.tmp"

for GRID in grid:16x16 grid:19x27; do
  DIR="$WORK/$(echo $GRID | tr ':' '-')"
  "$TACTILE" simulate --skin "$GRID" --subjects 5 --seed "$SEED" --out "$DIR" > /dev/null
  for PIPE in "grid:" "generic:per_channel=yes" "generic:"; do
    NAME=${PIPE%%:*}
    PARAMS=${PIPE#*:}
    CSV="$DIR/$NAME-$PARAMS.csv"
    "$TACTILE" features --pipeline "$NAME" ${PARAMS:+--params "$PARAMS"} --labels "$DIR/labels.db" \
      --threads 1 --out "$CSV" > "$DIR/features.txt" 2>&1
    COLUMNS=$(sed -n 's/.* rows x \([0-9]*\) features.*/\1/p' "$DIR/features.txt")
    for CLASSIFIER in $CLASSIFIERS; do
      echo "| $GRID | $NAME${PARAMS:+ ($PARAMS)} | $COLUMNS | $CLASSIFIER | $(accuracy "$CSV" "$CLASSIFIER") % |" >> "$OUT.tmp"
    done
  done
done

cat >> "$OUT.tmp" <<TEXT

Commands (one grid, one pipeline, one classifier):

    tactile simulate --skin grid:16x16 --subjects 5 --seed $SEED --out DIR
    tactile features --pipeline grid --labels DIR/labels.db --out grid.csv
    tactile features --pipeline generic --params per_channel=yes --labels DIR/labels.db --out generic.csv
    tactile evaluate --features grid.csv --classifier medium-tree --protocol loso --seed $SEED

\`generic\` without parameters (per_channel=auto) writes whole-grid columns on these grids
(256 and 513 channels > 64): its busiest-channel block, the neighbours' correlation, its
contact columns and the grid pipeline's 46. Classifiers: $CLASSIFIERS.
TEXT
mv "$OUT.tmp" "$OUT"
rm -rf "$WORK"
cat "$OUT"
