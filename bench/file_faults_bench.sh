#!/usr/bin/env bash
# Vanishing-file benchmark of issue 27 ("Faults of the world"): the headless workbench on a
# recording whose disk stops answering (a hung network share) or fails its reads (EIO, a
# pulled USB stick), injected through the script command `fault read` at --points different
# moments and places of the recording. Each run: the fault begins, the view moves to a time
# not read yet, frames are drawn, the disk comes back. Counted: crashes (exit status), the
# longest UI frame over the run, whether the window said why, and whether the file was read
# again after the fault.
# Usage: bench/file_faults_bench.sh [BUILD_DIR] [POINTS]
set -euo pipefail
build=${1:-build}
points=${2:-20}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo '{}' > "$work/settings.json"
# A long recording: 10 min of NAO's simulated skin (many chunks to read).
"$build/bin/tactile" simulate --skin nao --subjects 1 --repetitions 6 --seed 3 --out "$work/sim" >/dev/null
recording=$(ls "$work"/sim/*.h5 | head -1)
duration=$("$build/bin/tactile" info "$recording" | sed -n 's/.* samples, \([0-9.]*\) s$/\1/p' | head -1)
crashes=0 said=0 back=0 longest=0 worst=0
for ((point = 0; point < points; point++)); do
  mode=$([ $((point % 2)) -eq 0 ] && echo hang || echo fail)
  # Spread over the recording past its first chunk (32 s at 250 Hz), which "time 1" read before
  # the fault: a moment whose samples the window does not hold yet.
  at=$(python3 -c "print(round(40 + ($duration - 45) * (($point * 7919) % 97) / 97.0, 2))")
  cat > "$work/script.txt" <<SCRIPT
time 1
wait 3
fault read $mode
time $at
wait 6
state $work/during.json
fault read off
sleep 1.3
wait 3
time $at
wait 3
state $work/after.json
SCRIPT
  if ! "$build/bin/tactile-workbench-headless" "$recording" --size 1280x720 --settings "$work/settings.json" \
       --script "$work/script.txt" >/dev/null 2>"$work/stderr.txt"; then
    crashes=$((crashes + 1))
    continue
  fi
  read -r frame why again < <(python3 - "$work/during.json" "$work/after.json" <<'PY'
import json, sys
during, after = (json.load(open(p)) for p in sys.argv[1:3])
print(after["longest_frame_seconds"], int(bool(during["unavailable"])), int(after["unavailable"] == ""))
PY
)
  said=$((said + why))
  back=$((back + again))
  longest=$(python3 -c "print(max($longest, $frame))")
  printf '  %-4s at %7.2f s: longest frame %.3f s, said why %d, read again %d\n' "$mode" "$at" "$frame" "$why" "$again"
done
echo
echo "| runs (hang / fail alternating) | crashes | longest UI frame (s) | the window said why | the file was read again after |"
echo "|---:|---:|---:|---:|---:|"
printf '| %d | %d | %.3f | %d of %d | %d of %d |\n' "$points" "$crashes" "$longest" "$said" "$points" "$back" "$points"
