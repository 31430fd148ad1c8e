# shellcheck shell=bash
# A real single-node Slurm cluster for tests: munged, slurmctld and slurmd on
# localhost as plain background processes (no systemd), every file under one
# folder in /tmp, on two free ports. Source it, then:
#
#   cluster_start DIR     # DIR under /tmp; exports SLURM_CONF; waits for an idle node
#   cluster_wait_jobs SECONDS JOBID...   # until none of the jobs is queued or running
#   cluster_stop          # stops exactly the daemons cluster_start started
#
# Needs root (the daemons run as root) and Debian's slurmctld, slurmd,
# slurm-client and munge (scripts/setup.sh installs them). Slurm 22.05.

CLUSTER_DIR=
CLUSTER_MUNGED_PID=
CLUSTER_CTLD_PID=
CLUSTER_SLURMD_PID=

cluster_log() { echo "slurm-cluster: $*" >&2; }

cluster_alive() { # PID is running and not a zombie
  local state
  [ -n "$1" ] && [ -r "/proc/$1/stat" ] || return 1
  state=$(awk '{print $3}' "/proc/$1/stat" 2>/dev/null) || return 1
  [ -n "$state" ] && [ "$state" != Z ]
}

cluster_stop_pid() { # PID NAME: SIGTERM, up to 10 s, then SIGKILL; reap
  local pid=$1 name=$2
  [ -n "$pid" ] || return 0
  if cluster_alive "$pid"; then
    kill -TERM "$pid" 2>/dev/null || true
    for _ in $(seq 1 100); do
      cluster_alive "$pid" || break
      sleep 0.1
    done
    if cluster_alive "$pid"; then
      cluster_log "$name ($pid) ignored SIGTERM, sending SIGKILL"
      kill -KILL "$pid" 2>/dev/null || true
    fi
  fi
  wait "$pid" 2>/dev/null || true
}

cluster_stop() {
  cluster_stop_pid "$CLUSTER_SLURMD_PID" slurmd
  CLUSTER_SLURMD_PID=
  cluster_stop_pid "$CLUSTER_CTLD_PID" slurmctld
  CLUSTER_CTLD_PID=
  cluster_stop_pid "$CLUSTER_MUNGED_PID" munged
  CLUSTER_MUNGED_PID=
}

cluster_port_used() { # PORT appears as a local port in /proc/net/tcp{,6}
  local hex
  hex=$(printf '%04X' "$1")
  awk -v p=":$hex" 'NR > 1 && substr($2, length($2) - 4) == p { found = 1 } END { exit !found }' \
    /proc/net/tcp /proc/net/tcp6 2>/dev/null
}

cluster_free_port_pair() { # prints two consecutive free ports in 20000..59999, starting near a PID-derived one
  local port=$((20000 + ($$ * 37) % 40000))
  for _ in $(seq 1 200); do
    ((port + 1 < 60000)) || port=20000
    if ! cluster_port_used "$port" && ! cluster_port_used $((port + 1)); then
      echo "$port $((port + 1))"
      return 0
    fi
    port=$((port + 2))
  done
  return 1
}

cluster_dump_logs() {
  [ -n "$CLUSTER_DIR" ] || return 0
  local f
  for f in "$CLUSTER_DIR"/log/*; do
    [ -s "$f" ] || continue
    echo "---- $f (last 30 lines)" >&2
    tail -n 30 "$f" >&2
  done
}

cluster_start() { # DIR
  CLUSTER_DIR=$1
  case "$CLUSTER_DIR" in /tmp/?*) ;; *) cluster_log "cluster folder must be under /tmp, not '$CLUSTER_DIR'"; return 1 ;; esac
  local ports ctld_port slurmd_port node_hw host sock state
  ports=$(cluster_free_port_pair) || { cluster_log "no two free ports in 20000..59999"; return 1; }
  read -r ctld_port slurmd_port <<<"$ports"

  mkdir -p "$CLUSTER_DIR"/etc "$CLUSTER_DIR"/state "$CLUSTER_DIR"/spool "$CLUSTER_DIR"/log \
    "$CLUSTER_DIR"/munge/sock "$CLUSTER_DIR"/munge/priv
  chmod 755 "$CLUSTER_DIR" "$CLUSTER_DIR"/munge "$CLUSTER_DIR"/munge/sock # munged wants its socket folder a+x
  chmod 700 "$CLUSTER_DIR"/munge/priv                                       # and its key folder private
  sock=$CLUSTER_DIR/munge/sock/munge.socket.2

  host=$(hostname -s)
  # The node as slurmd sees it, e.g. "NodeName=vm CPUs=2 Boards=1 ... RealMemory=24105".
  node_hw=$(env -u SLURM_CONF slurmd -C | head -n 1)
  case "$node_hw" in NodeName=*) ;; *) cluster_log "slurmd -C printed '$node_hw'"; return 1 ;; esac

  export SLURM_CONF=$CLUSTER_DIR/etc/slurm.conf
  cat >"$SLURM_CONF" <<CONF
ClusterName=rockbaketest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$sock
StateSaveLocation=$CLUSTER_DIR/state
SlurmdSpoolDir=$CLUSTER_DIR/spool
SlurmctldPidFile=$CLUSTER_DIR/state/slurmctld.pid
SlurmdPidFile=$CLUSTER_DIR/spool/slurmd.pid
SlurmctldLogFile=$CLUSTER_DIR/log/slurmctld.log
SlurmdLogFile=$CLUSTER_DIR/log/slurmd.log
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
SchedulerParameters=batch_sched_delay=0
SwitchType=switch/none
MpiDefault=none
ReturnToService=2
MinJobAge=900
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
$node_hw NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=batch Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF

  mungekey --create --keyfile="$CLUSTER_DIR/munge/priv/munge.key" || return 1
  munged --foreground --key-file="$CLUSTER_DIR/munge/priv/munge.key" --socket="$sock" \
    --pid-file="$CLUSTER_DIR/munge/priv/munged.pid" --seed-file="$CLUSTER_DIR/munge/priv/munged.seed" \
    --log-file="$CLUSTER_DIR/log/munged.log" >"$CLUSTER_DIR/log/munged.out" 2>&1 &
  CLUSTER_MUNGED_PID=$!
  for _ in $(seq 1 100); do
    [ -S "$sock" ] && break
    cluster_alive "$CLUSTER_MUNGED_PID" || break
    sleep 0.1
  done
  munge -n -S "$sock" | unmunge -S "$sock" >/dev/null || { cluster_log "munged does not answer on $sock"; return 1; }

  slurmctld -D -f "$SLURM_CONF" >"$CLUSTER_DIR/log/slurmctld.out" 2>&1 &
  CLUSTER_CTLD_PID=$!
  slurmd -D -f "$SLURM_CONF" >"$CLUSTER_DIR/log/slurmd.out" 2>&1 &
  CLUSTER_SLURMD_PID=$!
  cluster_log "munged $CLUSTER_MUNGED_PID, slurmctld $CLUSTER_CTLD_PID (port $ctld_port)," \
    "slurmd $CLUSTER_SLURMD_PID (port $slurmd_port), files in $CLUSTER_DIR"

  state=
  for _ in $(seq 1 150); do # up to ~30 s for the node to register
    if ! cluster_alive "$CLUSTER_CTLD_PID" || ! cluster_alive "$CLUSTER_SLURMD_PID"; then
      cluster_log "a Slurm daemon exited at startup"
      return 1
    fi
    state=$(timeout 5 sinfo -h -N -o %T 2>/dev/null | head -n 1) || true
    [ "$state" = idle ] && return 0
    sleep 0.2
  done
  cluster_log "the node never became idle (last state '$state')"
  timeout 5 sinfo -N -l >&2 || true
  return 1
}

cluster_wait_jobs() { # SECONDS JOBID...: 0 once no job is queued or running, 1 on timeout
  local seconds=$1 deadline queued ids
  shift
  deadline=$((SECONDS + seconds))
  ids=$(
    IFS=,
    echo "$*"
  )
  while ((SECONDS < deadline)); do
    if ! cluster_alive "$CLUSTER_CTLD_PID" || ! cluster_alive "$CLUSTER_SLURMD_PID"; then
      cluster_log "a Slurm daemon exited while jobs $ids were queued or running"
      return 1
    fi
    if queued=$(timeout 10 squeue -h -j "$ids" -o %i 2>/dev/null); then
      [ -z "$queued" ] && return 0
    fi
    sleep 0.5
  done
  cluster_log "jobs $ids still queued or running after ${seconds}s:"
  timeout 10 squeue >&2 || true
  return 1
}
