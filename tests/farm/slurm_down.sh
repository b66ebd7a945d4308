#!/usr/bin/env bash
# Stops what slurm_up.sh DIR started, by the pids in its pid files, and waits for them to end.
dir=$1
if [ -f "$dir/slurm.conf" ]; then  # jobs first: their steps outlive slurmd
  SLURM_CONF="$dir/slurm.conf" scancel --quiet --user=root 2>/dev/null || true
  sleep 1
fi
for pidfile in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munge/munged.pid"; do
  [ -f "$pidfile" ] || continue
  pid=$(cat "$pidfile")
  kill "$pid" 2>/dev/null || continue
  for _ in $(seq 1 50); do
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  kill -9 "$pid" 2>/dev/null || true
done
exit 0
