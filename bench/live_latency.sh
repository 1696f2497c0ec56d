#!/usr/bin/env bash
# Online classification latency and agreement, per skin (issue "Live mode"): fits a model
# on simulated recordings (the skin's own features, ground-truth touches), then replays an
# unseen simulated recording at 1x through the live path and times, for each touch, its
# last sample's arrival to the final decision (build/bench/live_bench latency).
#   bench/live_latency.sh BUILD_DIR WORK_DIR [SECONDS]
set -euo pipefail
build=${1:?usage: live_latency.sh BUILD_DIR WORK_DIR [SECONDS]}
work=${2:?usage: live_latency.sh BUILD_DIR WORK_DIR [SECONDS]}
seconds=${3:-90}
tactile=$build/bin/tactile
declare -A pipeline=([nao]=kaboli [tsa]=tsa_event [fur]=fur [robovie]=robovie_xcorr [flux]=flux)
mkdir -p "$work"
for skin in nao tsa fur robovie flux; do
  train=$work/$skin-train test=$work/$skin-test
  if [[ ! -f $work/$skin-model.json ]]; then
    rm -rf "$train" "$test"
    "$tactile" simulate --skin "$skin" --subjects 4 --trials 1 --seed 1 --out "$train" > /dev/null
    "$tactile" simulate --skin "$skin" --subjects 1 --trials 1 --seed 7 --out "$test" > /dev/null
    "$tactile" features --pipeline "${pipeline[$skin]}" --labels "$train/labels.db" \
      --out "$work/$skin.csv" > /dev/null
    "$tactile" evaluate --features "$work/$skin.csv" --classifier linear-svm \
      --save-model "$work/$skin-model.json" > /dev/null
  fi
  recording=$(ls "$test"/*.h5 | head -1)
  "$build/bench/live_bench" latency "$work/$skin-model.json" "$recording" "$test/labels.db" "$seconds"
done
