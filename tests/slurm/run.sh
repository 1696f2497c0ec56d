#!/usr/bin/env bash
# ctest's entry to the Slurm test (label `slurm`): tests/slurm/cluster_test.sh on a local
# one-node cluster that scripts/slurm-local.sh starts and removes. Exits 77 (skipped) where
# there is no Slurm to run or no root to run it as.
#
#   tests/slurm/run.sh SOURCE_DIR TACTILE
set -euo pipefail
source_dir=$1
tactile=$2
if ! command -v slurmctld >/dev/null 2>&1 && [[ ! -x /usr/sbin/slurmctld ]]; then
  echo "SKIPPED: slurmctld is not installed (Debian packages slurm-wlm and munge;" \
    "scripts/install-deps.sh)"
  exit 77
fi
if [[ $(id -u) -ne 0 ]]; then
  echo "SKIPPED: a local Slurm needs root (slurmd starts jobs as their user); run as root"
  exit 77
fi
exec "$source_dir/scripts/slurm-local.sh" run -- "$source_dir/tests/slurm/cluster_test.sh" "$tactile"
