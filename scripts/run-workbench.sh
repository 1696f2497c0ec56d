#!/usr/bin/env bash
# `make run`: opens the workbench on the demo workspace; with no display it renders
# the main window headless to build/screenshot.png instead.
set -euo pipefail
build_dir=${1:-build}
exec "$build_dir/bin/tactile-workbench"
