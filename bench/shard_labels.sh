#!/usr/bin/env bash
# What sharding costs for the commands that write labels (issue 29): each command run as one
# process, then as N shards one after another and `tactile merge`, in one run, so the figures
# are ratios: (sum of the shards' wall times) / one process, and the merge / one process.
# On a cluster the shards run side by side: the wall time is then about the slowest shard
# plus the merge.
#   simulate: fur, SUBJECTS subjects (one recording each);
#   segment:  those recordings, each skin's own segmenter;
#   predict:  a knn:k=1 model of the fur pipeline on them;
#   verify:   the folder (recordings and labels.db).
# Usage: bench/shard_labels.sh BUILD [SUBJECTS] [N] [DATA_DIR]
set -euo pipefail
build=${1:?usage: bench/shard_labels.sh BUILD [SUBJECTS] [N] [DATA_DIR]}
subjects=${2:-12}
count=${3:-3}
data=${4:-/tmp/tactile-shard-labels}
tactile="$build/bin/tactile"
rm -rf "$data" && mkdir -p "$data"
seconds() {  # command... -> wall seconds of one run
  local start end
  start=$(date +%s.%N)
  "$@" > /dev/null 2>&1 || true
  end=$(date +%s.%N)
  echo "$end - $start" | bc -l
}
# name, one-process seconds, shards' seconds (sum), merge seconds
report() { printf "| %-8s | %6.2f | %6.2f | %5.2f | %6.2f | %5.2f |\n" "$1" "$2" "$3" \
  "$(echo "$3 / $2" | bc -l)" "$4" "$(echo "$4 / $2" | bc -l)"; }
parts() { for ((i = 1; i <= count; ++i)); do echo "$1.part-$i-of-$count"; done; }
shards() {  # command words... (the shard flag appended) -> summed seconds
  local total=0
  for ((i = 1; i <= count; ++i)); do
    total=$(echo "$total + $(seconds "$@" --shard "$i/$count")" | bc -l)
  done
  echo "$total"
}
echo "| command  | one process (s) | $count shards, summed (s) | ratio | merge (s) | merge / one |"
echo "|----------|------:|------:|------:|------:|------:|"
sim="simulate --skin fur --subjects $subjects"
one=$(seconds "$tactile" $sim --out "$data/one")
sum=$(shards "$tactile" $sim --out "$data/sharded")
merge=$(seconds "$tactile" merge $(parts "$data/sharded/simulate"))
report simulate "$one" "$sum" "$merge"
cmp "$data/one/labels.db" "$data/sharded/labels.db" || echo "labels.db differ!"
"$tactile" features --pipeline fur --labels "$data/one/labels.db" --out "$data/f.csv" > /dev/null 2>&1
"$tactile" evaluate --features "$data/f.csv" --classifier knn:k=1 --protocol kfold:2 \
  --pipeline fur --save-model "$data/model.json" > /dev/null 2>&1
for command in segment predict; do
  cp "$data/one/labels.db" "$data/$command-one.db"
  cp "$data/one/labels.db" "$data/$command-sharded.db"
  words=("$tactile" "$command" "$data/one")
  [[ $command == predict ]] && words+=(--model "$data/model.json")
  one=$(seconds "${words[@]}" --labels "$data/$command-one.db")
  sum=$(shards "${words[@]}" --labels "$data/$command-sharded.db")
  merge=$(seconds "$tactile" merge $(parts "$data/$command-sharded.db.$command"))
  report "$command" "$one" "$sum" "$merge"
done
one=$(seconds "$tactile" verify "$data/one" --out "$data/verify-one.json")
sum=$(shards "$tactile" verify "$data/one" --out "$data/verify.json")
merge=$(seconds "$tactile" merge $(parts "$data/verify.json"))
report verify "$one" "$sum" "$merge"
cmp "$data/verify-one.json" "$data/verify.json" || echo "verify reports differ!"
