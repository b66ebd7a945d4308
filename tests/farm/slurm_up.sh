#!/usr/bin/env bash
# Starts a single-node Slurm cluster for the farm tests, everything under DIR: munged (its own
# socket), slurmctld and slurmd with a slurm.conf written here (linuxproc tracking, no cgroups,
# unused ports). Prints "SLURM_CONF=DIR/slurm.conf" and the munge socket when the node is idle.
# Stop it with slurm_down.sh DIR (by the daemons' pid files). Needs root, slurm-wlm and munge.
set -euo pipefail
dir=$(realpath "$1")
mkdir -p "$dir/state" "$dir/spool" "$dir/munge"
host=$(hostname -s)
free_port() {
  python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}
ctld_port=$(free_port)
d_port=$(free_port)
while [ "$d_port" = "$ctld_port" ]; do d_port=$(free_port); done
cpus=$(nproc)

# munged: the machine's key, a socket and pid file of our own.
key=/etc/munge/munge.key
[ -f "$key" ] || mungekey --create --keyfile="$key"
munged --force --socket="$dir/munge/munge.socket" --pid-file="$dir/munge/munged.pid" \
  --log-file="$dir/munge/munged.log" --seed-file="$dir/munge/munged.seed" --key-file="$key"

cat > "$dir/slurm.conf" <<CONF
ClusterName=sylvatest
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SlurmctldPort=$ctld_port
SlurmdPort=$d_port
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1
MinJobAge=300
NodeName=$host CPUs=$cpus RealMemory=4000 State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$dir/slurm.conf"
slurmctld
slurmd
for _ in $(seq 1 60); do
  if sinfo -h -o %T 2>/dev/null | grep -q idle; then
    echo "SLURM_CONF=$SLURM_CONF"
    exit 0
  fi
  sleep 0.5
done
echo "slurm_up: the node did not come up within 30 s; see $dir/*.log" >&2
exit 1
