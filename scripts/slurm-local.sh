#!/usr/bin/env bash
# A single-node Slurm on this machine for tests and benchmarks, with nothing left behind
# (docs/CLUSTER.md, "A local cluster").
#
#   scripts/slurm-local.sh run -- CMD ARGS...   start a cluster in a fresh temp folder, run CMD
#                                               with SLURM_CONF exported, stop every daemon,
#                                               remove the folder, exit with CMD's code
#   scripts/slurm-local.sh start DIR            start one in DIR (created; must be empty) and
#                                               print the line to export for sbatch/squeue
#   scripts/slurm-local.sh stop DIR             stop the daemons started in DIR (DIR is kept)
#
# It runs its own munged (socket, key, pid and log in the folder), slurmctld and slurmd on free
# ports, with no cgroups (proctrack/linuxproc, task/none), no system service and no file
# outside the folder. Needs root: slurmd starts each job as the user who submitted it.
# Accounting: Slurm 22.05 has no accounting store without slurmdbd, so the job completion log
# (jobcomp/filetxt, DIR/jobcomp.log) is kept instead; `sacct --completion` reads it.
set -euo pipefail

program=$(basename "$0")

usage() {
  sed -n '4,10p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
}

die() {
  echo "$program: $*" >&2
  exit 1
}

# What is missing to run a cluster here, said by name.
check_requirements() {
  local missing=()
  for tool in munged slurmctld slurmd sinfo squeue scancel; do
    command -v "$tool" >/dev/null 2>&1 || [[ -x /usr/sbin/$tool ]] || missing+=("$tool")
  done
  if [[ ${#missing[@]} -gt 0 ]]; then
    die "missing ${missing[*]}: install the Debian packages slurm-wlm and munge" \
      "(scripts/install-deps.sh)"
  fi
  if [[ $(id -u) -ne 0 ]]; then
    die "needs root: slurmd must start jobs as the submitting user; run it under sudo" \
      "(or as root in a container/CI job)"
  fi
}

# A TCP port on the loopback that nobody holds now (the kernel picks it).
free_port() {
  if [[ -x /usr/bin/python3 ]]; then
    /usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("", 0)); print(s.getsockname()[1])'
  else
    shuf -i 20000-60999 -n 1  # without Python: a random high port, most likely free
  fi
}

sbin() { command -v "$1" 2>/dev/null || echo "/usr/sbin/$1"; }

# Writes the munge key and slurm.conf into $1 and starts munged, slurmctld and slurmd there;
# returns when sinfo shows the node idle.
start_cluster() {
  local dir=$1
  mkdir -p "$dir"/{spool,state,log}
  chmod 700 "$dir"
  local node
  node=$(hostname -s)

  # munged refuses a key anyone else can read.
  head -c 1024 /dev/urandom >"$dir/munge.key"
  chmod 400 "$dir/munge.key"
  "$(sbin munged)" --force --socket="$dir/munge.socket" --key-file="$dir/munge.key" \
    --pid-file="$dir/munged.pid" --log-file="$dir/log/munged.log" --seed-file="$dir/munge.seed" ||
    die "munged did not start (see $dir/log/munged.log)"

  # This machine as slurmd sees it (CPUs, sockets, cores, memory), minus its uptime.
  local hardware
  hardware=$("$(sbin slurmd)" -C | head -n 1 | sed "s/^NodeName=[^ ]* //")
  local controller_port node_port
  controller_port=$(free_port)
  node_port=$(free_port)
  while [[ $node_port == "$controller_port" ]]; do node_port=$(free_port); done

  cat >"$dir/slurm.conf" <<EOF
# Written by scripts/slurm-local.sh: a one-node cluster living in $dir.
ClusterName=tactile-local
SlurmctldHost=$node
SlurmctldPort=$controller_port
SlurmdPort=$node_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool/slurmd-%n
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
# No cgroups: processes are tracked through /proc, tasks are not bound.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
MpiDefault=none
# Jobs share the node by cores, so the tasks of an array run side by side.
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
# Look at waiting jobs (a merge whose shards just ended) every 2 s, not every minute.
SchedulerParameters=sched_interval=2,bf_interval=1
ReturnToService=2
# No slurmdbd: no accounting store; finished jobs go to the completion log instead, and their
# records stay in slurmctld for MinJobAge seconds (scontrol show job).
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$dir/jobcomp.log
MinJobAge=600
NodeName=$node NodeAddr=127.0.0.1 $hardware State=UNKNOWN
PartitionName=local Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF

  export SLURM_CONF=$dir/slurm.conf
  "$(sbin slurmctld)" -f "$dir/slurm.conf" || die "slurmctld did not start (see $dir/log/slurmctld.log)"
  "$(sbin slurmd)" -f "$dir/slurm.conf" || die "slurmd did not start (see $dir/log/slurmd.log)"

  local state=""
  for _ in $(seq 1 60); do
    state=$(sinfo -h -n "$node" -o %T 2>/dev/null | head -n 1 || true)
    [[ $state == idle ]] && return 0
    sleep 0.5
  done
  echo "$program: the node is not idle after 30 s (state '${state:-none}'); logs:" >&2
  tail -n 20 "$dir/log/slurmctld.log" "$dir/log/slurmd.log" >&2 || true
  return 1
}

# Sends TERM to the daemon whose pid file is $1 and waits until it is gone (KILL after 10 s).
stop_daemon() {
  local pid_file=$1
  [[ -f $pid_file ]] || return 0
  local pid
  pid=$(cat "$pid_file" 2>/dev/null || true)
  [[ $pid =~ ^[0-9]+$ ]] || return 0
  kill -TERM "$pid" 2>/dev/null || return 0
  for _ in $(seq 1 100); do
    kill -0 "$pid" 2>/dev/null || return 0
    sleep 0.1
  done
  kill -KILL "$pid" 2>/dev/null || true
}

# Cancels the cluster's jobs, then stops slurmd, slurmctld and munged of folder $1.
stop_cluster() {
  local dir=$1
  if [[ -f $dir/slurm.conf && -f $dir/slurmctld.pid ]]; then
    export SLURM_CONF=$dir/slurm.conf
    local jobs
    jobs=$(squeue -h -o %A 2>/dev/null || true)
    if [[ -n $jobs ]]; then
      # shellcheck disable=SC2086
      scancel $jobs 2>/dev/null || true
      for _ in $(seq 1 50); do
        [[ -z $(squeue -h -o %A 2>/dev/null || true) ]] && break
        sleep 0.2
      done
    fi
  fi
  stop_daemon "$dir/slurmd.pid"
  stop_daemon "$dir/slurmctld.pid"
  stop_daemon "$dir/munged.pid"
}

[[ $# -ge 1 ]] || usage
case $1 in
  run)
    shift
    [[ ${1:-} == -- ]] && shift
    [[ $# -ge 1 ]] || usage
    check_requirements
    dir=$(mktemp -d "${TMPDIR:-/tmp}/slurm-local-XXXXXX")
    cleanup() {
      local code=$?
      trap - EXIT INT TERM
      stop_cluster "$dir"
      rm -rf "$dir"
      exit "$code"
    }
    trap cleanup EXIT
    trap 'exit 130' INT
    trap 'exit 143' TERM
    start_cluster "$dir" || exit 1
    echo "$program: cluster up (node $(hostname -s), SLURM_CONF=$SLURM_CONF)" >&2
    set +e
    "$@"
    code=$?
    set -e
    exit "$code"
    ;;
  start)
    [[ $# -eq 2 ]] || usage
    check_requirements
    dir=$(realpath -m "$2")
    if [[ -d $dir && -n $(ls -A "$dir") ]]; then die "$dir is not empty"; fi
    # Whatever started is stopped again if the rest fails.
    trap 'stop_cluster "$dir"' EXIT
    start_cluster "$dir" || exit 1
    trap - EXIT
    echo "$program: cluster up in $dir; to use it:"
    echo "export SLURM_CONF=$dir/slurm.conf"
    echo "$program: stop it with: $0 stop $dir"
    ;;
  stop)
    [[ $# -eq 2 ]] || usage
    dir=$(realpath -m "$2")
    [[ -f $dir/slurm.conf ]] || die "$dir holds no cluster started by $program"
    stop_cluster "$dir"
    echo "$program: stopped the daemons of $dir (remove the folder when done)"
    ;;
  *) usage ;;
esac
