#!/usr/bin/env bash
# A one-node Slurm cluster on this machine, for testing the sweep's Slurm
# path for real: munged, slurmctld and slurmd, all as root, all state, logs,
# sockets and the configuration in one folder (nothing under /etc is touched).
#
#   scripts/slurm_cluster.sh start [DIR]    # default DIR /tmp/atssim-slurm
#   scripts/slurm_cluster.sh stop [DIR]     # stops the three daemons it started
#   scripts/slurm_cluster.sh status [DIR]
#
# Clients find it through SLURM_CONF=DIR/slurm.conf (`start` prints the
# export line). Needs root; installs slurm-wlm and munge when missing
# (scripts/setup.sh slurm). Ports 16817/16818 on 127.0.0.1.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
action="${1:-}"
dir="${2:-/tmp/atssim-slurm}"
conf="$dir/slurm.conf"

die() { echo "slurm_cluster: $*" >&2; exit 1; }
alive() { [ -f "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null; }

stop_daemon() {  # pid file, name
  if alive "$1"; then
    local pid
    pid="$(cat "$1")"
    kill "$pid"
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -0 "$pid" 2>/dev/null && kill -9 "$pid"
    echo "slurm_cluster: stopped $2 (pid $pid)" >&2
  fi
  rm -f "$1"
}

case "$action" in
  start)
    [ "$(id -u)" -eq 0 ] || die "run as root (the daemons and jobs run as root)"
    bash "$here/setup.sh" slurm
    mkdir -p "$dir/ctld" "$dir/spool"
    chmod 700 "$dir"
    host="$(hostname -s)"
    if [ ! -f "$dir/munge.key" ]; then
      dd if=/dev/urandom of="$dir/munge.key" bs=1024 count=1 status=none
      chmod 400 "$dir/munge.key"
    fi
    # The node as slurmd sees it (CPUs, sockets, cores), without RealMemory.
    node="$(slurmd -C | head -1 | sed 's/ RealMemory=[0-9]*//')"
    cat > "$conf" <<CONF
ClusterName=atssim
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=16817
SlurmdPort=16818
AuthType=auth/munge
AuthInfo=socket=$dir/munge.socket
StateSaveLocation=$dir/ctld
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
$node NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=atssim Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
    alive "$dir/munged.pid" || munged --force --key-file="$dir/munge.key" --socket="$dir/munge.socket" \
      --pid-file="$dir/munged.pid" --log-file="$dir/munged.log" --seed-file="$dir/munge.seed"
    alive "$dir/slurmctld.pid" || slurmctld -f "$conf"
    alive "$dir/slurmd.pid" || slurmd -f "$conf"
    export SLURM_CONF="$conf"
    for _ in $(seq 100); do
      state="$(sinfo -h -o %T 2>/dev/null || true)"
      case "$state" in idle*|mixed*|allocated*) break ;; esac
      sleep 0.2
    done
    case "$state" in
      idle*|mixed*|allocated*) ;;
      *) echo "slurm_cluster: the node did not come up (state '$state'); logs in $dir" >&2
         tail -5 "$dir/slurmctld.log" "$dir/slurmd.log" >&2 || true
         exit 1 ;;
    esac
    echo "slurm_cluster: one node '$host' ($state) up; pids munged $(cat "$dir/munged.pid")," \
         "slurmctld $(cat "$dir/slurmctld.pid"), slurmd $(cat "$dir/slurmd.pid")" >&2
    echo "export SLURM_CONF=$conf"
    ;;
  stop)
    stop_daemon "$dir/slurmd.pid" slurmd
    stop_daemon "$dir/slurmctld.pid" slurmctld
    stop_daemon "$dir/munged.pid" munged
    ;;
  status)
    for d in munged slurmctld slurmd; do
      if alive "$dir/$d.pid"; then echo "$d: running (pid $(cat "$dir/$d.pid"))"; else echo "$d: stopped"; fi
    done
    [ -f "$conf" ] && SLURM_CONF="$conf" sinfo 2>/dev/null || true
    ;;
  *) sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2 ;;
esac
