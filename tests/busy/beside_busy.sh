#!/bin/sh
# Runs a test program beside busy processes, as on a desktop where a compiler or a browser
# keeps the cores busy (issue 41): `beside_busy.sh COUNT PROGRAM ARGS...`. The workbench's jobs
# must finish in their fair share of the machine, not wait for it to be idle. The loops stop
# with the test, however it ends.
count=$1
shift
pids=""
trap 'kill $pids 2>/dev/null' EXIT INT TERM
i=0
while [ "$i" -lt "$count" ]; do
  sh -c 'while :; do :; done' &
  pids="$pids $!"
  i=$((i + 1))
done
"$@"
