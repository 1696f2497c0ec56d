#!/usr/bin/env bash
# What a Slurm job array costs and gains on this machine (issue 29): `tactile evaluate
# --classifier all --protocol kfold:5` on 40 simulated fur recordings, as one process and as
# 1, 2 and 4 shards through `tactile cluster slurm --submit` on the local one-node cluster
# (scripts/slurm-local.sh), wall time from submission until the merge has written the result;
# plus the features table (1 s of work) as 4 shards: mostly the scheduler's own cost. Writes bench/compare/SLURM.md. Needs root (slurmd).
#
#   bench/slurm_bench.sh [BUILD_DIR]
set -euo pipefail
build=$(realpath "${1:-build}")
out=$(pwd)/bench/compare/SLURM.md
[[ -n ${SLURM_CONF:-} ]] || exec scripts/slurm-local.sh run -- "$0" "$build"

tactile=$build/bin/tactile
work=$(mktemp -d /tmp/slurm-bench.XXXXXX)
trap 'rm -rf "$work"' EXIT
cd "$work"
now() { date +%s.%N; }
seconds() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", b - a }'; }

"$tactile" simulate --skin fur --subjects 10 --trials 4 --out recordings >/dev/null
"$tactile" features --pipeline fur --labels recordings/labels.db --recordings recordings \
  --out table.csv >/dev/null
evaluate="evaluate --features table.csv --classifier all --protocol kfold:5 --no-timings"

# Runs the evaluation through Slurm as $1 shards (threads $2 each); prints the seconds from
# submission until the merge completed.
sharded() {
  local folder=jobs-$1-$2 start merge state
  start=$(now)
  "$tactile" cluster slurm --command "tactile $evaluate --threads $2 --out sharded-$1-$2.json" \
    --shards "$1" --out "$folder" --submit >/dev/null
  merge=$(grep -o '"merge": "[0-9]*"' "$folder/jobs.json" | grep -o '[0-9]\+')
  for _ in $(seq 1 3000); do
    state=$(squeue --noheader --states=all --jobs="$merge" --format=%T 2>/dev/null || true)
    [[ $state == COMPLETED || $state == FAILED || $state == CANCELLED ]] && break
    sleep 0.1
  done
  [[ $state == COMPLETED ]] || { echo "merge of $1 shards: $state" >&2; exit 1; }
  cmp -s one.json "sharded-$1-$2.json" || { echo "$1 shards differ from one process" >&2; exit 1; }
  seconds "$start" "$(now)"
}

start=$(now)
"$tactile" $evaluate --threads 1 --out one.json >/dev/null
one_thread=$(seconds "$start" "$(now)")
start=$(now)
"$tactile" $evaluate --out one-all.json >/dev/null
one_all=$(seconds "$start" "$(now)")
rows=()
for shards in 1 2 4; do
  rows+=("| $shards shards, 1 thread each | $(sharded "$shards" 1) |")
done

# Mostly the scheduler: 4 shards of the features table (1 s of work in one process).
start=$(now)
"$tactile" cluster slurm --command "tactile features --pipeline fur --labels recordings/labels.db \
--recordings recordings --out small.csv" --shards 4 --out jobs-small --submit >/dev/null
merge=$(grep -o '"merge": "[0-9]*"' jobs-small/jobs.json | grep -o '[0-9]\+')
for _ in $(seq 1 600); do
  state=$(squeue --noheader --states=all --jobs="$merge" --format=%T 2>/dev/null || true)
  [[ $state == COMPLETED || $state == FAILED || $state == CANCELLED ]] && break
  sleep 0.1
done
[[ $state == COMPLETED ]] || { echo "features merge: $state" >&2; exit 1; }
small=$(seconds "$start" "$(now)")

cd - >/dev/null
{
  echo "# Slurm job arrays on the local one-node cluster"
  echo
  echo "Made by \`bench/slurm_bench.sh\` on $(date -u +%Y-%m-%d), $(nproc) cores, one run:"
  echo "\`tactile $evaluate\` on 40 simulated fur recordings (1200 rows)."
  echo "Sharded rows: wall time from \`tactile cluster slurm --submit\` until the merge job has"
  echo "completed (scheduler passes every 2 s, scripts/slurm-local.sh); every sharded result is"
  echo "byte-identical to one process's."
  echo
  echo "| run | seconds |"
  echo "|---|---|"
  echo "| one process, 1 thread | $one_thread |"
  echo "| one process, every core | $one_all |"
  printf '%s\n' "${rows[@]}"
  echo "| features (1 s in one process) as 4 shards: mostly the scheduler's cost | $small |"
  echo
  echo "$(uptime | sed 's/.*load average/Load average during the run/'): the machine was shared."
} >"$out"
cat "$out"
