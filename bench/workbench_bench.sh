#!/usr/bin/env bash
# The workbench's targets on long recordings (issue "The workbench grows up"), measured in
# one run so the figures are read as ratios:
#   - open to first frame of the headless workbench, 1 h and 1 min of Robovie's 274 films
#     at 100 Hz, and an empty workbench (renderer start alone); median of 5 runs each;
#   - a signal-plot frame (8 channels, 1200 px, zooming and panning, the skin's 274 values
#     read at the cursor) over 10 h against 1 min: the same views (up to 60 s wide) on
#     both, and on 10 h also zoomed out to all of it; vertices per pixel column per channel;
#   - peak resident memory of that browsing process.
# Usage: bench/workbench_bench.sh [BUILD_DIR] [DATA_DIR]   (the data is made once, ~1 GB)
set -euo pipefail
build=${1:-build}
data=${2:-/tmp/tactile-workbench-bench}
"$build/bench/workbench_bench" make "$data"
headless="$build/bin/tactile-workbench-headless"
settings=$(mktemp)
median_seconds() {  # command... -> median wall seconds of 5 runs
  local times=()
  for _ in 1 2 3 4 5; do
    local start end
    start=$(date +%s.%N)
    "$@" >/dev/null 2>&1
    end=$(date +%s.%N)
    times+=("$(echo "$end - $start" | bc -l)")
  done
  printf '%s\n' "${times[@]}" | sort -g | sed -n 3p
}
out=$(mktemp --suffix .png)
empty=$(median_seconds "$headless" --frames 1 --settings "$settings" --screenshot "$out")
minute=$(median_seconds "$headless" "$data/minute.h5" --frames 1 --settings "$settings" --screenshot "$out")
hour=$(median_seconds "$headless" "$data/hour.h5" --frames 1 --settings "$settings" --screenshot "$out")
ten=$(median_seconds "$headless" "$data/ten-hours.h5" --frames 1 --settings "$settings" --screenshot "$out")
printf 'open to first frame (s): empty %.3f, 1 min %.3f, 1 h %.3f, 10 h %.3f\n' "$empty" "$minute" "$hour" "$ten"
printf '  1 h / 1 min = %.2fx (target <= 1.5x); 1 h beyond renderer start = %.3f s (target <= 0.3 s)\n' \
  "$(echo "$hour / $minute" | bc -l)" "$(echo "$hour - $empty" | bc -l)"
browse_minute=$("$build/bench/workbench_bench" browse "$data/minute.h5")
browse_ten_same=$("$build/bench/workbench_bench" browse "$data/ten-hours.h5" 60)
browse_ten=$("$build/bench/workbench_bench" browse "$data/ten-hours.h5")
echo "browse 1 min:                  $browse_minute"
echo "browse 10 h, views up to 60 s: $browse_ten_same"
echo "browse 10 h, views up to 10 h: $browse_ten"
python3 - "$browse_minute" "$browse_ten_same" "$browse_ten" <<'PY'
import json, sys
minute, same, ten = (json.loads(text) for text in sys.argv[1:4])
def ratio(a, b, key):
    return f"{a[key + '_median'] / b[key + '_median']:.2f}x median, {a[key + '_p90'] / b[key + '_p90']:.2f}x p90"
print(f"  plot frame, same views (zoom 60 s -> 2 s, pan, zoom out), 10 h / 1 min: "
      f"{ratio(same, minute, 'frame_ms')} (target <= 1.1x)")
print(f"  plot frame zooming out to all 10 h / 1 min: {ratio(ten, minute, 'frame_ms')}; the workbench's "
      f"own work (data + draw list): {ratio(ten, minute, 'build_ms')} "
      f"({ten['build_ms_median']:.2f} ms vs {minute['build_ms_median']:.2f} ms)")
print(f"  vertices per pixel column per channel: at most "
      f"{max(r['vertices_per_column_per_channel_max'] for r in (minute, same, ten)):.2f} (target <= 4)")
print(f"  peak resident memory browsing 10 h: {ten['peak_rss_mb']:.0f} MB, 1 min: "
      f"{minute['peak_rss_mb']:.0f} MB (target <= 250 MB)")
PY
rm -f "$settings" "$out"
