#!/usr/bin/env bash
# End to end on a real (local) Slurm: `tactile features` and `tactile evaluate` as 4 shards
# each through `tactile cluster slurm --submit` give byte-identical files to one process; a
# failed shard and a cancelled one keep their merge from running, `tactile merge` names the
# missing shard, and `tactile cluster resubmit` of that shard alone completes the job.
# Run under scripts/slurm-local.sh (SLURM_CONF set); tests/slurm/run.sh does that for ctest.
#
#   tests/slurm/cluster_test.sh TACTILE
set -euo pipefail

tactile=$(realpath "$1")
work=$(mktemp -d "${TMPDIR:-/tmp}/tactile-slurm-test-XXXXXX")
trap 'rm -rf "$work"' EXIT
cd "$work"

fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# The merge job id of the last submission in DIR/jobs.json.
merge_job() { grep -o '"merge": "[0-9]*"' "$1/jobs.json" | tail -n 1 | grep -o '[0-9]\+'; }
array_job() { grep -o '"array": "[0-9]*"' "$1/jobs.json" | tail -n 1 | grep -o '[0-9]\+'; }

# The state slurmctld holds for job $1 ("" once it has forgotten it).
job_state() { squeue --noheader --array --states=all --jobs="$1" --format=%T 2>/dev/null | head -n 1; }

# Waits until job $1 has ended, up to $2 seconds; prints its final state.
wait_for_job() {
  local state=""
  for _ in $(seq 1 $(($2 * 5))); do
    state=$(job_state "$1")
    case $state in
      COMPLETED | FAILED | CANCELLED | TIMEOUT | OUT_OF_MEMORY | NODE_FAIL) break ;;
    esac
    sleep 0.2
  done
  echo "$state"
}

echo "== one process"
"$tactile" simulate --skin fur --subjects 10 --trials 4 --out recordings >/dev/null
features=(features --pipeline fur --labels recordings/labels.db --recordings recordings)
evaluate=(evaluate --features one.csv --classifier all --protocol kfold:5 --no-timings)
"$tactile" "${features[@]}" --out one.csv >/dev/null
"$tactile" "${evaluate[@]}" --out one.json >/dev/null

echo "== features: 4 shards, shard 3 made to fail (its part path is a folder)"
# The scripts first, so that the part can be blocked before the jobs run.
features_command="tactile ${features[*]} --out 'sharded table.csv'"
"$tactile" cluster slurm --command "$features_command" --shards 4 --out jobs-features >/dev/null
mkdir jobs-features/parts/part-3-of-4
"$tactile" cluster slurm --command "$features_command" --shards 4 --out jobs-features --submit

echo "== evaluate: 4 shards, shard 2 cancelled while it runs"
"$tactile" cluster slurm --command "tactile ${evaluate[*]} --out sharded.json" --shards 4 \
  --out jobs-evaluate --submit
evaluate_array=$(array_job jobs-evaluate)
for _ in $(seq 1 300); do
  [[ $(job_state "${evaluate_array}_2") == RUNNING ]] && break
  sleep 0.2
done
[[ $(job_state "${evaluate_array}_2") == RUNNING ]] || fail "shard 2 of evaluate never ran"
scancel "${evaluate_array}_2"

echo "== the merges wait on shards that failed"
[[ $(wait_for_job "$(array_job jobs-features)_3" 60) == FAILED ]] || fail "features shard 3 did not fail"
[[ $(wait_for_job "${evaluate_array}_2" 30) == CANCELLED ]] || fail "evaluate shard 2 was not cancelled"
for shard in 1 2 4; do
  [[ $(wait_for_job "$(array_job jobs-features)_$shard" 60) == COMPLETED ]] ||
    fail "features shard $shard did not complete"
done
for shard in 1 3 4; do
  [[ $(wait_for_job "${evaluate_array}_$shard" 90) == COMPLETED ]] ||
    fail "evaluate shard $shard did not complete"
done
sleep 3  # a scheduler pass, in which a merge that could run would start
for folder in jobs-features jobs-evaluate; do
  state=$(job_state "$(merge_job $folder)")
  [[ $state == PENDING || $state == CANCELLED ]] || fail "$folder: the merge ran ($state)"
done
[[ ! -e "sharded table.csv" && ! -e sharded.json ]] || fail "a merge wrote its result"

status=$("$tactile" cluster status jobs-features)
echo "$status"
grep -q '^shard 3/4 .* failed .*part missing' <<<"$status" || fail "status does not show shard 3 failed"
grep -q '^shard 1/4 .* completed .*part present' <<<"$status" || fail "status does not show shard 1 done"
grep -q 'missing: shard 3' <<<"$status" || fail "status does not name the missing part"
status=$("$tactile" cluster status jobs-evaluate)
echo "$status"
grep -q '^shard 2/4 .* cancelled' <<<"$status" || fail "status does not show shard 2 cancelled"

echo "== tactile merge by hand names the missing shard"
if message=$("$tactile" merge jobs-evaluate/parts/part-{1,3,4}-of-4 --out by-hand.json 2>&1); then
  fail "merge of 3 of 4 parts succeeded"
fi
echo "$message"
grep -q 'shard 2/4 .*is missing' <<<"$message" || fail "merge did not name shard 2/4"
[[ ! -e by-hand.json ]] || fail "merge wrote a result from 3 parts"

echo "== resubmit the failed shards alone"
rmdir jobs-features/parts/part-3-of-4
"$tactile" cluster resubmit jobs-features --shard 3
"$tactile" cluster resubmit jobs-evaluate --shard 2
[[ $(wait_for_job "$(merge_job jobs-features)" 60) == COMPLETED ]] || fail "features merge did not complete"
[[ $(wait_for_job "$(merge_job jobs-evaluate)" 90) == COMPLETED ]] || fail "evaluate merge did not complete"
"$tactile" cluster status jobs-evaluate

cmp one.csv "sharded table.csv" || fail "features: 4 shards differ from one process"
cmp one.json sharded.json || fail "evaluate: 4 shards differ from one process"
echo "PASS: features and evaluate on 4 Slurm shards, after a failed and a cancelled shard" \
  "resubmitted, are byte-identical to one process"
