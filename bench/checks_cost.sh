#!/usr/bin/env bash
# What the file checks of format 2 cost (issue "Files that cannot lie"): the same jobs
# run by a build from before the checks on the files it writes (format 1) and by this
# build on its own files (format 2), interleaved in one run so the figures are ratios.
#   - open to first frame of the headless workbench on a 1-hour Robovie recording
#     (274 channels, 100 Hz), median of 7;
#   - browsing it (workbench_bench browse: zoom, pan, the skin read at the cursor);
#   - `tactile features --pipeline kaboli` over a simulated NAO corpus (5 subjects, 52 MB),
#     one thread, median of 5.
# Usage: bench/checks_cost.sh OLD_BUILD NEW_BUILD [DATA_DIR]
set -euo pipefail
old=${1:?usage: bench/checks_cost.sh OLD_BUILD NEW_BUILD [DATA_DIR]}
new=${2:?usage: bench/checks_cost.sh OLD_BUILD NEW_BUILD [DATA_DIR]}
data=${3:-/tmp/tactile-checks-cost}
mkdir -p "$data/old" "$data/new"
for side in old new; do
  build=${!side}
  "$build/bench/workbench_bench" make "$data/$side" > /dev/null
  [[ -d "$data/$side/nao" ]] || "$build/bin/tactile" simulate --skin nao --subjects 5 \
      --out "$data/$side/nao" > /dev/null
done
settings=$(mktemp)
png=$(mktemp --suffix .png)
seconds() {  # command... -> wall seconds of one run
  local start end
  start=$(date +%s.%N)
  "$@" > /dev/null 2>&1
  end=$(date +%s.%N)
  echo "$end - $start" | bc -l
}
median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
declare -A open_times features_times
for round in 1 2 3 4 5 6 7; do
  for side in old new; do
    build=${!side}
    open_times[$side]+="$(seconds "$build/bin/tactile-workbench-headless" "$data/$side/hour.h5" \
        --frames 1 --settings "$settings" --screenshot "$png") "
  done
done
for round in 1 2 3 4 5; do
  for side in old new; do
    build=${!side}
    features_times[$side]+="$(seconds "$build/bin/tactile" features --pipeline kaboli \
        --labels "$data/$side/nao/labels.db" --threads 1 --out "$data/$side/features.csv") "
  done
done
browse_old=$("$old/bench/workbench_bench" browse "$data/old/hour.h5" 60)
browse_new=$("$new/bench/workbench_bench" browse "$data/new/hour.h5" 60)
open_old=$(echo "${open_times[old]}" | tr ' ' '\n' | grep . | median)
open_new=$(echo "${open_times[new]}" | tr ' ' '\n' | grep . | median)
features_old=$(echo "${features_times[old]}" | tr ' ' '\n' | grep . | median)
features_new=$(echo "${features_times[new]}" | tr ' ' '\n' | grep . | median)
ls -l "$data/old/hour.h5" "$data/new/hour.h5"
printf 'open to first frame, 1 h: format 1 %.3f s, format 2 %.3f s: %.3fx\n' \
  "$open_old" "$open_new" "$(echo "$open_new / $open_old" | bc -l)"
printf 'tactile features kaboli over 5 NAO recordings: format 1 %.3f s, format 2 %.3f s: %.3fx\n' \
  "$features_old" "$features_new" "$(echo "$features_new / $features_old" | bc -l)"
python3 - "$browse_old" "$browse_new" <<'PY'
import json, sys
old, new = (json.loads(text) for text in sys.argv[1:3])
for key in ("frame_ms", "build_ms"):
    print(f"browse 1 h, {key}: format 1 {old[key + '_median']:.3f} ms, format 2 "
          f"{new[key + '_median']:.3f} ms: {new[key + '_median'] / old[key + '_median']:.3f}x median, "
          f"{new[key + '_p90'] / old[key + '_p90']:.3f}x p90")
PY
rm -f "$settings" "$png"
