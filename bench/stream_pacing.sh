#!/usr/bin/env bash
# Is stream-sim paced, not bursted? For each skin with a packet format: a listener on a free
# port (stream-listen, port 0, --bound-to), one second of the skin sent at 1x, and the figures
# of time: the sender's first-to-last seconds (about 1 when paced; near 0 when bursted) and
# the received rate as a ratio of the device's. The tests (tests/cli/stream_cli_test.cpp) check
# what arrives by count; how long it took is measured here, where a busy machine is not a
# failure.
#   bench/stream_pacing.sh BUILD_DIR
set -euo pipefail
build=${1:?usage: stream_pacing.sh BUILD_DIR}
tactile=$build/bin/tactile
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf '%-6s %10s %14s %14s\n' skin datagrams "sent seconds" "rate / device"
for pair in nao:250 fur:15 flux:100; do
  skin=${pair%%:*} device=${pair##*:}
  rm -f "$work/bound"
  "$tactile" stream-listen --skin "$skin" --from udp://127.0.0.1:0 --bound-to "$work/bound" \
    --duration 30 --idle 2 > "$work/heard.txt" &
  listener=$!
  for _ in $(seq 300); do [[ -s $work/bound ]] && break; sleep 0.05; done
  "$tactile" stream-sim --skin "$skin" --to "$(cat "$work/bound")" --rate-factor 1 --duration 1 \
    > "$work/sent.txt"
  wait "$listener"
  seconds=$(awk -F': ' '$1=="seconds"{print $2}' "$work/sent.txt")
  rate=$(awk -F': ' '$1=="rate"{split($2, a, " "); print a[1]}' "$work/heard.txt")
  datagrams=$(awk -F': ' '$1=="datagrams"{print $2}' "$work/heard.txt")
  printf '%-6s %10s %14s %14.3f\n' "$skin" "$datagrams" "$seconds" "$(echo "$rate / $device" | bc -l)"
done
