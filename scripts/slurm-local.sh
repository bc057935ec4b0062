#!/usr/bin/env bash
# A real single-node Slurm cluster on this machine, for the render farm's test and for trying `sylva farm`
# without a cluster (docs/farm.md). Everything lives under STATE: the configuration, munge's key and socket,
# the daemons' state, logs and pid files; nothing under /etc is touched and no systemd is needed.
#
#   scripts/slurm-local.sh start STATE   starts munged, slurmctld and slurmd; waits until the node is idle and a
#                                        canary job has run; prints `export SLURM_CONF=STATE/slurm.conf`
#   scripts/slurm-local.sh stop STATE    cancels every job, stops the daemons it started (by their pid files)
#
# Needs root and the packages slurmctld slurmd slurm-client munge (scripts/setup-debian.sh). Exit 77 when they
# are missing, so a test can skip. Ports 6817/6818 must be free. A start after a run that was killed half-way
# first stops what that run left behind (through the pid files, never by process name).
set -euo pipefail

usage() {
  echo "usage: $0 start|stop STATE_DIR" >&2
  exit 2
}
[ $# -eq 2 ] || usage
action=$1
state=$(realpath -m "$2")
conf=$state/slurm.conf

# The pid in pid file $1 when it is still the program $2 (checked in /proc, so a recycled pid is never
# signalled).
pid_of() {
  local file=$1 name=$2 pid
  [ -f "$file" ] || return 0
  pid=$(cat "$file" 2>/dev/null || true)
  [[ $pid =~ ^[0-9]+$ ]] || return 0
  [ "$(cat /proc/"$pid"/comm 2>/dev/null || true)" = "$name" ] && echo "$pid"
  return 0
}

# Sends SIGTERM to the pids given, waits up to 10 s for all of them, then SIGKILL.
stop_pids() {
  [ $# -gt 0 ] || return 0
  kill "$@" 2>/dev/null || true
  for _ in $(seq 100); do
    local alive=0 pid
    for pid in "$@"; do
      [ -d /proc/"$pid" ] && alive=1
    done
    [ "$alive" = 0 ] && return 0
    sleep 0.1
  done
  kill -9 "$@" 2>/dev/null || true
}

stop() {
  if [ -f "$conf" ] && [ -f "$state/slurmctld.pid" ]; then
    # Jobs first: `scontrol shutdown` leaves running job steps alive.
    SLURM_CONF=$conf scancel --quiet --user="$(id -un)" 2>/dev/null || true
    for _ in $(seq 50); do
      [ -z "$(SLURM_CONF=$conf squeue -h -t running,completing 2>/dev/null || true)" ] && break
      sleep 0.1
    done
  fi
  # All three at once: one after the other takes seconds longer.
  # shellcheck disable=SC2046
  stop_pids $(pid_of "$state/slurmd.pid" slurmd) $(pid_of "$state/slurmctld.pid" slurmctld) \
    $(pid_of "$state/munge/munged.pid" munged)
  rm -f "$state/slurmd.pid" "$state/slurmctld.pid" "$state/munge/munged.pid"
}

if [ "$action" = stop ]; then
  stop
  exit 0
fi
[ "$action" = start ] || usage

for program in munged mungekey slurmctld slurmd sbatch squeue scontrol sinfo scancel; do
  if ! command -v "$program" >/dev/null 2>&1 && [ ! -x /usr/sbin/"$program" ]; then
    echo "slurm-local: $program not found (install slurmctld slurmd slurm-client munge: scripts/setup-debian.sh)" >&2
    exit 77
  fi
done
if [ "$(id -u)" -ne 0 ]; then
  echo "slurm-local: needs root (the daemons run as root here)" >&2
  exit 77
fi
export PATH=$PATH:/usr/sbin

stop # leftovers of an earlier run in the same state folder
rm -rf "$state"
mkdir -p "$state"/{munge,ctld,d,logs}
chmod 700 "$state/munge"
host=$(hostname -s)

umask 022
mungekey --create --keyfile="$state/munge/munge.key" >/dev/null 2>&1
chmod 400 "$state/munge/munge.key"
munged --key-file="$state/munge/munge.key" --socket="$state/munge/munge.socket" \
  --pid-file="$state/munge/munged.pid" --log-file="$state/munge/munged.log" \
  --seed-file="$state/munge/munged.seed" --force
munge -n -S "$state/munge/munge.socket" | unmunge -S "$state/munge/munge.socket" >/dev/null

# The node line from what slurmd measures, without RealMemory (a value above what slurmd measures drains the
# node) and with the cores this machine has.
node=$(slurmd -C | head -n 1 | sed -e 's/ RealMemory=[0-9]*//' -e "s/^NodeName=[^ ]*/NodeName=$host NodeAddr=127.0.0.1/")
cat >"$conf" <<EOF
# Written by scripts/slurm-local.sh: a single-node cluster for tests (docs/farm.md).
ClusterName=local
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$state/munge/munge.socket
StateSaveLocation=$state/ctld
SlurmdSpoolDir=$state/d
SlurmctldPidFile=$state/slurmctld.pid
SlurmdPidFile=$state/slurmd.pid
SlurmctldLogFile=$state/logs/slurmctld.log
SlurmdLogFile=$state/logs/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
MpiDefault=none
MailProg=/bin/true
ReturnToService=2
MinJobAge=3600
SchedulerParameters=batch_sched_delay=0
DependencyParameters=kill_invalid_depend
$node State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$conf
slurmctld
slurmd

# Ready when the node is idle and a canary job has created its file (a job recorded COMPLETED without having
# run is how a broken process tracker shows).
ready=""
for _ in $(seq 300); do
  if [ "$(sinfo -h -o %T 2>/dev/null || true)" = idle ]; then
    ready=1
    break
  fi
  sleep 0.1
done
if [ -z "$ready" ]; then
  echo "slurm-local: the node did not become idle within 30 s (logs in $state/logs)" >&2
  stop
  exit 1
fi
sbatch --quiet --output=/dev/null --wrap="touch '$state/canary'" >/dev/null
for _ in $(seq 300); do
  [ -e "$state/canary" ] && break
  sleep 0.1
done
if [ ! -e "$state/canary" ]; then
  echo "slurm-local: the canary job did not run within 30 s (logs in $state/logs)" >&2
  stop
  exit 1
fi
echo "export SLURM_CONF=$conf"
