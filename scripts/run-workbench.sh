#!/usr/bin/env bash
# `make run`: opens the workbench on the demo workspace, creating it on the first run.
# With no display the workbench says so and renders its main window headless to
# build/screenshot.png instead.
set -euo pipefail
build_dir=${1:-build}
demo_dir="$build_dir/demo"
if [[ ! -f "$demo_dir/labels.db" ]]; then
  echo "run: creating the demo workspace in $demo_dir"
  "$build_dir/bin/tactile" simulate --demo "$demo_dir" --video  # each recording filmed (docs/VIDEO.md)
fi
exec "$build_dir/bin/tactile-workbench" "$demo_dir"
