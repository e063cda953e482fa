# A one-node Slurm cluster on this machine for tests (issue 44); source this file, then
#   slurm_cluster_start DIR   munged, slurmctld and slurmd with every file (key, socket, configuration, state,
#                             spool, logs, pid files) in DIR, on loopback ports that were free; exports SLURM_CONF
#   slurm_cluster_stop DIR    stops the three daemons by their pid files (safe to call twice, or after a failed start)
# No systemd and nothing outside DIR: the daemons run as the calling user (root: slurmd must start job steps as the
# job's user), with proctrack/pgid and task/none (no cgroups), no accounting database: finished jobs are written by
# jobcomp/filetxt to DIR/jobcomp.txt, which `sacct --completion` reads.
# Needs Debian's munge, slurmctld, slurmd and slurm-client (tools/bootstrap installs them).

slurm_cluster_available() {
  command -v munged > /dev/null && command -v mungekey > /dev/null && command -v slurmctld > /dev/null &&
    command -v slurmd > /dev/null && command -v sbatch > /dev/null && command -v sacct > /dev/null
}

# Two TCP ports on 127.0.0.1 that were free a moment ago.
_slurm_free_ports() {
  python3 -c '
import socket
sockets = [socket.socket() for _ in range(2)]
for s in sockets:
    s.bind(("127.0.0.1", 0))
print(" ".join(str(s.getsockname()[1]) for s in sockets))'
}

_slurm_wait_for() {  # _slurm_wait_for SECONDS COMMAND...: retries COMMAND every 0.2 s
  local tries=$(($1 * 5))
  shift
  for ((i = 0; i < tries; i++)); do
    "$@" > /dev/null 2>&1 && return 0
    sleep 0.2
  done
  return 1
}

slurm_cluster_start() {
  local dir=$1
  mkdir -p "$dir/munge" "$dir/state" "$dir/spool" "$dir/log"
  chmod 700 "$dir/munge"
  mungekey --create --keyfile="$dir/munge/munge.key" || return 1
  # --force: the socket's folder sits under /tmp, which munged otherwise refuses as writable by others.
  munged --force --socket="$dir/munge/socket" --key-file="$dir/munge/munge.key" --pid-file="$dir/munge/munged.pid" \
    --log-file="$dir/log/munged.log" --seed-file="$dir/munge/seed" || return 1

  local ports cpus memory
  ports=($(_slurm_free_ports))
  cpus=$(nproc)
  # The node's memory as slurmd measures it, less 1 GB for the daemons and the test itself.
  memory=$(slurmd -C | sed -n 's/.*RealMemory=\([0-9]*\).*/\1/p')
  memory=$((memory > 2048 ? memory - 1024 : memory))
  cat > "$dir/slurm.conf" << EOF
ClusterName=lfsptest
SlurmctldHost=localhost
SlurmctldPort=${ports[0]}
SlurmdPort=${ports[1]}
SlurmUser=$(id -un)
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/pgid
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$dir/jobcomp.txt
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
MpiDefault=none
ReturnToService=2
MinJobAge=600
KillWait=5
InactiveLimit=0
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=test Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF=$dir/slurm.conf
  # -i: ignore any state a previous cluster left (there is none: the folder is new).
  slurmctld -i -f "$dir/slurm.conf" || return 1
  slurmd -N localhost -f "$dir/slurm.conf" || return 1
  # Ready when the node is idle (it registers with the controller after both have started).
  _slurm_wait_for 60 bash -c 'sinfo -h -n localhost -o %T | grep -q -x idle' || {
    echo "the test cluster's node did not become idle:"
    sinfo 2>&1 | tail -5
    tail -20 "$dir/log/slurmctld.log" "$dir/log/slurmd.log" 2>/dev/null
    return 1
  }
}

_slurm_stop_pid_file() {  # _slurm_stop_pid_file FILE: TERM the daemon named in FILE, KILL it after 10 s
  local file=$1 pid
  [ -s "$file" ] || return 0
  pid=$(cat "$file")
  kill "$pid" 2> /dev/null || return 0
  for ((i = 0; i < 50; i++)); do
    kill -0 "$pid" 2> /dev/null || return 0
    sleep 0.2
  done
  kill -9 "$pid" 2> /dev/null || true
}

slurm_cluster_stop() {
  local dir=$1
  # Jobs first (slurmd kills their processes), then the daemons: slurmd, slurmctld, munged.
  [ -s "$dir/slurmctld.pid" ] && scancel --full -u "$(id -un)" > /dev/null 2>&1 && sleep 1
  _slurm_stop_pid_file "$dir/slurmd.pid"
  _slurm_stop_pid_file "$dir/slurmctld.pid"
  _slurm_stop_pid_file "$dir/munge/munged.pid"
  return 0
}
