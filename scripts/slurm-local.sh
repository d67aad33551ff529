#!/usr/bin/env bash
# A real single-node Slurm cluster on localhost (Debian's slurm 22.05 + munge), for the tests and for
# trying the farm feature without a farm. Everything it writes (slurm.conf, munge key and socket,
# state, spool, pid files, logs) lives under DIR; nothing under /etc is touched.
#
#   bash scripts/slurm-local.sh install       apt-get the packages if sbatch/slurmctld/slurmd/munged are missing
#   bash scripts/slurm-local.sh start DIR     start munged, slurmctld and slurmd; wait for the node to be idle;
#                                             print `export SLURM_CONF=DIR/slurm.conf` (for eval) on stdout
#   bash scripts/slurm-local.sh stop DIR      cancel its jobs, stop the three daemons; fine if already stopped
#   bash scripts/slurm-local.sh status DIR    sinfo and squeue against DIR's cluster
#
# Typical use:
#   bash scripts/slurm-local.sh install
#   eval "$(bash scripts/slurm-local.sh start /tmp/weft-slurm)"
#   sbatch --array=0-3 job.sh; squeue
#   bash scripts/slurm-local.sh stop /tmp/weft-slurm
#
# Runs as root (SlurmUser=root, SlurmdUser=root). One cluster at a time per port pair: set
# SLURM_LOCAL_CTLD_PORT / SLURM_LOCAL_SLURMD_PORT (default 6817 / 6818) to run two side by side.
# The node is the local `hostname -s` at 127.0.0.1, with CPUs = nproc, one task per CPU.
# Requeue one array task with `scontrol requeue JOBID_TASK` (running or finished tasks; a pending
# one is refused). It may start again after AuthInfo's cred_expire + 1 s (Slurm's default 120 s;
# SLURM_LOCAL_CRED_EXPIRE, default 10, Slurm's minimum 5); `scontrol update JobId=JOBID_TASK
# StartTime=now` right after the requeue skips the wait. A requeued job's output file is truncated
# unless sbatch --open-mode=append. No accounting: `sacct` fails ("Slurm accounting storage is
# disabled"); use `squeue -r -t all -j JOBID`, which lists finished tasks too for MinJobAge
# (SLURM_LOCAL_MIN_JOB_AGE, default 300 s), then "Invalid job id specified".
set -euo pipefail

ctld_port=${SLURM_LOCAL_CTLD_PORT:-6817}
slurmd_port=${SLURM_LOCAL_SLURMD_PORT:-6818}
cred_expire=${SLURM_LOCAL_CRED_EXPIRE:-10}
min_job_age=${SLURM_LOCAL_MIN_JOB_AGE:-300}
start_timeout=${SLURM_LOCAL_START_TIMEOUT:-60}

die() { echo "slurm-local: $*" >&2; exit 1; }
log() { echo "slurm-local: $*" >&2; }  # stdout is kept for the export line

usage() {
  sed -n '2,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "${BASH_SOURCE[0]}" >&2
  exit 2
}

missing_programs() {
  local p
  for p in sbatch squeue sinfo scontrol scancel slurmctld slurmd munged munge; do
    command -v "$p" >/dev/null 2>&1 || printf '%s ' "$p"
  done
}

cmd_install() {
  local missing
  missing=$(missing_programs)
  [[ -z $missing ]] && return 0
  log "missing: $missing; installing slurmctld slurmd slurm-client munge"
  command -v apt-get >/dev/null 2>&1 || die "no apt-get here; install Slurm (slurmctld, slurmd, client tools) and munge by hand"
  [[ $(id -u) -eq 0 ]] || die "installing needs root (apt-get)"
  # The minimal set (the slurm-wlm metapackage pulls these plus extras we do not use).
  if ! DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
         slurmctld slurmd slurm-client munge >&2; then
    log "apt-get install failed; retrying after apt-get update"
    apt-get update >&2 || die "apt-get update failed"
    DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
      slurmctld slurmd slurm-client munge >&2 || die "apt-get install slurmctld slurmd slurm-client munge failed"
  fi
  missing=$(missing_programs)
  [[ -z $missing ]] || die "still missing after install: $missing"
}

# Paths of one cluster, all under $dir (absolute, so the config does not depend on the cwd).
set_paths() {
  [[ -n ${1:-} ]] || usage
  dir=$(realpath -m -- "$1")
  [[ $dir != *[[:space:]]* ]] || die "DIR must not contain spaces (slurm.conf cannot quote them): $dir"
  conf=$dir/slurm.conf
  munge_dir=$dir/munge
  munge_socket=$munge_dir/munge.socket
  munge_key=$munge_dir/munge.key
  run_dir=$dir/run
  log_dir=$dir/log
  munged_pid=$run_dir/munged.pid
  slurmctld_pid=$run_dir/slurmctld.pid
  slurmd_pid=$run_dir/slurmd.pid
  node=$(hostname -s)
  [[ -n $node ]] || die "hostname -s is empty"
}

# Whether process $1 exists and is not a zombie (PID 1 may be slow to reap, or not reap at all).
alive() {
  local stat
  stat=$(cat "/proc/$1/stat" 2>/dev/null) || return 1
  stat=${stat##*) }
  [[ -n $stat && ${stat:0:1} != Z ]]
}

# The pid in pid file $1 when that process is alive and its command is $2 (a stale pid file whose
# pid was reused by something else must not get killed).
live_pid() {
  local pid comm
  [[ -s $1 ]] || return 1
  pid=$(<"$1")
  [[ $pid =~ ^[0-9]+$ ]] || return 1
  comm=$(cat "/proc/$pid/comm" 2>/dev/null) || return 1
  [[ $comm == "$2" ]] && alive "$pid" || return 1
  echo "$pid"
}

port_busy() { (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }

write_conf() {
  local cpus mem_mb margin_mb
  cpus=$(nproc)
  mem_mb=$(( $(awk '/^MemTotal:/ {print $2}' /proc/meminfo) / 1024 ))
  # slurmd drains a node that reports less memory than configured: leave a margin (10 %, >= 256 MB).
  margin_mb=$(( mem_mb / 10 > 256 ? mem_mb / 10 : 256 ))
  mem_mb=$(( mem_mb > 2 * margin_mb ? mem_mb - margin_mb : mem_mb / 2 ))
  cat >"$conf" <<EOF
# Written by scripts/slurm-local.sh start; regenerated on every start.
ClusterName=weftlocal
# Address 127.0.0.1 explicitly: the hostname need not resolve (or may resolve to another interface).
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
# Our own munged; cred_expire is also how long a requeued job waits before it may start again.
AuthInfo=socket=$munge_socket,cred_expire=$cred_expire
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$slurmctld_pid
SlurmdPidFile=$slurmd_pid
SlurmctldLogFile=$log_dir/slurmctld.log
SlurmdLogFile=$log_dir/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
# No cgroups in a container: track processes by parent pid, no task binding, no accounting.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
# The default /bin/mail is usually absent and slurmctld logs an error for it.
MailProg=/bin/true
# One job per CPU: CR_CPU with only CPUs= on the node (no socket/core/thread layout), so that
# hyper-threads are handed out one at a time too.
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
# Scheduling passes every 2 s instead of 60/30 s: a requeued job whose begin time has passed is
# otherwise only looked at again when some other job event happens.
SchedulerParameters=sched_interval=2,bf_interval=2
ReturnToService=2
JobRequeue=1
MinJobAge=$min_job_age
# Short timeouts: fast start, fast stop, fast detection of a dead slurmd.
MessageTimeout=5
SlurmctldTimeout=10
SlurmdTimeout=10
InactiveLimit=0
KillWait=5
WaitTime=0
TCPTimeout=2
NodeName=$node NodeAddr=127.0.0.1 NodeHostname=$node CPUs=$cpus RealMemory=$mem_mb State=UNKNOWN
PartitionName=weft Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
}

start_munged() {
  mkdir -p "$munge_dir"
  # Others need x on the socket's directory to submit as non-root; the key itself stays 0400.
  chmod 755 "$munge_dir"
  if [[ ! -s $munge_key ]]; then
    # A private key per cluster; 1 KiB of random data is what mungekey makes by default.
    (umask 077; head -c 1024 /dev/urandom >"$munge_key")
  fi
  chmod 400 "$munge_key"
  # Root is fine for munged. --force turns its permission checks into warnings: without it, it refuses
  # a DIR below a world-writable directory without the sticky bit ("Logfile is insecure").
  munged --force \
    --socket="$munge_socket" --key-file="$munge_key" --pid-file="$munged_pid" \
    --log-file="$log_dir/munged.log" --seed-file="$munge_dir/munge.seed" \
    || start_failed "munged failed to start"
  local i
  for ((i = 0; i < 50; i++)); do
    munge -n -S "$munge_socket" 2>/dev/null | unmunge -S "$munge_socket" >/dev/null 2>&1 && return 0
    sleep 0.1
  done
  start_failed "munged does not answer on $munge_socket"
}

print_tails() {
  local f
  for f in "$log_dir"/munged.log "$log_dir"/slurmctld.log "$log_dir"/slurmd.log; do
    [[ -f $f ]] || continue
    echo "==> $f <==" >&2
    tail -n 25 "$f" >&2
  done
}

# Show why, and leave no half-started cluster behind.
start_failed() {
  log "$1"
  print_tails
  cmd_stop "$dir"
  die "start failed (logs in $log_dir)"
}

node_state() { SLURM_CONF=$conf sinfo -h -n "$node" -o %t 2>/dev/null | head -n 1; }

cmd_start() {
  set_paths "${1:-}"
  [[ $(id -u) -eq 0 ]] || die "start needs root (SlurmUser=root, SlurmdUser=root)"
  [[ -z $(missing_programs) ]] || die "Slurm or munge missing; run: bash scripts/slurm-local.sh install"
  if live_pid "$slurmctld_pid" slurmctld >/dev/null || live_pid "$slurmd_pid" slurmd >/dev/null \
     || live_pid "$munged_pid" munged >/dev/null; then
    die "a cluster is already running in $dir; stop it first: bash scripts/slurm-local.sh stop $dir"
  fi
  local p
  for p in "$ctld_port" "$slurmd_port"; do
    port_busy "$p" && die "port $p is in use (another slurm-local cluster or a system Slurm?); stop it, or set SLURM_LOCAL_CTLD_PORT / SLURM_LOCAL_SLURMD_PORT"
  done
  mkdir -p "$dir/state" "$dir/spool" "$run_dir" "$log_dir"
  write_conf
  local t0=$SECONDS
  start_munged
  # SLURM_CONF in the daemons' environment too: the slurmstepds they fork inherit it, and
  # stop finds stray ones by it.
  export SLURM_CONF=$conf
  slurmctld -f "$conf" || start_failed "slurmctld failed to start"
  slurmd -f "$conf" -N "$node" || start_failed "slurmd failed to start"
  local state=
  while ((SECONDS - t0 < start_timeout)); do
    state=$(node_state)
    [[ $state == idle ]] && break
    sleep 0.5
  done
  [[ $state == idle ]] || start_failed "node $node not idle after ${start_timeout}s (state: ${state:-no answer})"
  log "node $node idle after $((SECONDS - t0))s; partition weft, $(nproc) CPUs; logs in $log_dir"
  echo "export SLURM_CONF=$conf"
}

# TERM daemons (pairs of pid file and command name) together, wait for them to go; KILL after ~15 s.
stop_daemons() {
  local pids=() files=() pid i
  while (($# >= 2)); do
    if pid=$(live_pid "$1" "$2"); then
      kill -TERM "$pid" 2>/dev/null || true
      pids+=("$pid")
    fi
    files+=("$1")
    shift 2
  done
  for pid in "${pids[@]}"; do
    for ((i = 0; i < 150; i++)); do
      alive "$pid" || break
      sleep 0.1
    done
    if alive "$pid"; then
      log "$(cat "/proc/$pid/comm" 2>/dev/null) ($pid) ignored SIGTERM; killing it"
      kill -KILL "$pid" 2>/dev/null || true
      while alive "$pid"; do sleep 0.1; done
    fi
  done
  rm -f "${files[@]}"
}

# slurmstepds forked by this cluster's slurmd (they carry its SLURM_CONF in their environment).
our_stepds() {
  local pid
  for pid in $(pgrep -x slurmstepd 2>/dev/null); do
    alive "$pid" || continue
    { tr '\0' '\n' <"/proc/$pid/environ"; } 2>/dev/null | grep -qxF "SLURM_CONF=$conf" && echo "$pid"
  done
  return 0
}

kill_tree() {
  local child
  for child in $(pgrep -P "$1" 2>/dev/null); do kill_tree "$child"; done
  kill -KILL "$1" 2>/dev/null || true
}

cmd_stop() {
  set_paths "${1:-}"
  local jobs=() i pid
  # Cancel the jobs first: slurmd leaves its slurmstepds (and the jobs) running when it stops.
  if live_pid "$slurmctld_pid" slurmctld >/dev/null; then
    mapfile -t jobs < <(SLURM_CONF=$conf squeue -h -o %A 2>/dev/null | sort -u)
    if ((${#jobs[@]})); then
      SLURM_CONF=$conf scancel "${jobs[@]}" 2>/dev/null || true
      for ((i = 0; i < 100; i++)); do
        [[ -z $(our_stepds) ]] && break
        sleep 0.1
      done
    fi
  fi
  # Both Slurm daemons at once; munged last, they talk through it while shutting down.
  stop_daemons "$slurmd_pid" slurmd "$slurmctld_pid" slurmctld
  for pid in $(our_stepds); do
    log "killing leftover slurmstepd $pid and its processes"
    kill_tree "$pid"
  done
  stop_daemons "$munged_pid" munged
}

cmd_status() {
  set_paths "${1:-}"
  [[ -f $conf ]] || die "no cluster in $dir (no slurm.conf)"
  live_pid "$slurmctld_pid" slurmctld >/dev/null || die "slurmctld of $dir is not running"
  export SLURM_CONF=$conf
  sinfo
  echo
  squeue
}

case ${1:-} in
  install) cmd_install ;;
  start) cmd_start "${2:-}" ;;
  stop) cmd_stop "${2:-}" ;;
  status) cmd_status "${2:-}" ;;
  *) usage ;;
esac
