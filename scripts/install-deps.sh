#!/usr/bin/env bash
# Installs the Debian packages that the build, the workbench and the tests need.
# Idempotent: checks each package and installs only the missing ones, with one
# `apt-get update` when anything is missing. Says what it does.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  ninja-build mold lld ccache  # the build's generator, linker and compiler cache (docs/TESTING.md)
  libeigen3-dev nlohmann-json3-dev libcli11-dev
  libhdf5-dev libsqlite3-dev zlib1g-dev libsvm-dev
  libtinyxml2-dev  # ELAN .eaf label files (docs/INTEROP.md)
  libmatio-dev libedf-dev libxdf-dev  # MATLAB .mat, EDF+/BDF+ and XDF recordings (docs/IMPORT.md)
  libavformat-dev libavcodec-dev libswscale-dev libavutil-dev libavdevice-dev  # video (docs/VIDEO.md)
  libxgboost-dev  # the boosted-trees preset (XGBoost's C API)
  libimgui-dev libstb-dev libglfw3-dev libgl-dev libgl1-mesa-dri libosmesa6-dev
  googletest libgtest-dev libgmock-dev libbenchmark-dev
  xvfb xauth
  python3-h5py  # a test reads our recordings with h5py, as users do
  clang-format  # scripts/format.sh --check: CI fails on code clang-format would change
  clang libclang-rt-dev  # scripts/fuzz.sh: libFuzzer and the sanitizers' runtime for clang
  slurm-wlm munge  # scripts/slurm-local.sh and `ctest -L slurm`: a one-node Slurm (docs/CLUSTER.md)
)

missing=()
for package in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$package" 2>/dev/null || true)
  if [[ "$status" != "install ok installed" ]]; then
    missing+=("$package")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then
  sudo_cmd=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
echo "install-deps: done"
