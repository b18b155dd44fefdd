#!/usr/bin/env bash
# Bring up / tear down a throw-away one-host Slurm cluster (slurmctld + slurmd +
# munged) whose keys, config, state, logs, sockets and pid files all live in one
# directory. Used by the automated tests of `rtrt farm` and by people who want
# to try `rtrt farm` locally without a real cluster.
#
#   tools/slurm_cluster.sh up DIR     # prints: export SLURM_CONF=DIR/slurm.conf
#   tools/slurm_cluster.sh down DIR
#
# Exit status: 0 ok, 2 usage error, 3 Slurm cannot be started here (tests skip).
set -euo pipefail

readonly PROG=slurm_cluster
readonly CLUSTER=rtrt-local
readonly PARTITION=rtrt
readonly NODE=localhost
readonly UP_TIMEOUT=30   # seconds to wait for the node to become idle
readonly STOP_TIMEOUT=10 # seconds between SIGTERM and SIGKILL

usage() {
    cat <<EOF
Usage: $0 up DIR | down DIR | --help

  up DIR    Start a one-host Slurm cluster ("$CLUSTER") as root; everything it
            needs (munge key, slurm.conf, state, spool, logs, sockets, pid
            files) is kept in DIR, an absolute path (created if missing).
            Prints one line on stdout:  export SLURM_CONF=DIR/slurm.conf
            so that  eval "\$($0 up DIR)"  points the Slurm commands at it.
  down DIR  Cancel its jobs and stop the daemons started by 'up DIR'.
            Idempotent.

Exit status: 0 success; 2 usage error; 3 Slurm cannot be started here (a
package missing, not root, a daemon died, the node never became idle), with
a line "$PROG: cannot start a Slurm cluster here: REASON" on stderr.
Needs: slurmctld slurmd munged (Debian: slurm-wlm munge), run as root.
EOF
}

die_usage() {
    echo "$PROG: $*" >&2
    echo "Try '$0 --help'." >&2
    exit 2
}

# ---------------------------------------------------------------- paths ----
set_paths() {
    DIR=$1
    CONF=$DIR/slurm.conf
    GRES_CONF=$DIR/gres.conf
    PLUGSTACK=$DIR/plugstack.conf
    MUNGE_DIR=$DIR/munge
    MUNGE_KEY=$MUNGE_DIR/munge.key
    MUNGE_SOCKET=$DIR/munge.socket
    MUNGE_PID=$DIR/run/munged.pid
    MUNGE_LOG=$DIR/log/munged.log
    MUNGE_SEED=$MUNGE_DIR/munged.seed
    STATE_DIR=$DIR/state
    SPOOL_DIR=$DIR/spool
    CTLD_PID=$DIR/run/slurmctld.pid
    SLURMD_PID=$DIR/run/slurmd.pid
    CTLD_LOG=$DIR/log/slurmctld.log
    SLURMD_LOG=$DIR/log/slurmd.log
}

check_dir_arg() {
    local dir=${1:-}
    [[ -n $dir ]] || die_usage "missing DIR"
    [[ $dir == /* ]] || die_usage "DIR must be an absolute path: $dir"
    # Strip trailing slashes so the paths written into slurm.conf are tidy.
    while [[ $dir == */ && $dir != / ]]; do dir=${dir%/}; done
    [[ $dir != / ]] || die_usage "DIR must not be /"
    # slurm.conf has no robust quoting and AuthInfo is comma separated, so
    # keep DIR to plain characters.
    [[ $dir =~ ^[A-Za-z0-9._/+-]+$ ]] ||
        die_usage "DIR may only contain letters, digits and ._/+- : $dir"
    # Unix socket paths are limited to 107 bytes; slurmd creates step sockets
    # named DIR/spool/localhost_<jobid>.<stepid> (up to ~38 more bytes).
    ((${#dir} <= 64)) || die_usage "DIR is too long (${#dir} > 64 chars) for Unix socket paths: $dir"
    printf '%s\n' "$dir"
}

# ------------------------------------------------------------ processes ----
# is_alive PID: running and not a zombie (pid 1 here may reap lazily).
is_alive() {
    local stat
    kill -0 "$1" 2>/dev/null || return 1
    stat=$(cat "/proc/$1/stat" 2>/dev/null) || return 1
    stat=${stat##*) }
    [[ ${stat:0:1} != Z ]]
}

# pid_of PIDFILE NAME: print the pid in PIDFILE if that process is alive and
# really is NAME (guards against a stale pid file and a recycled pid).
pid_of() {
    local file=$1 name=$2 pid comm
    [[ -r $file ]] || return 1
    pid=$(tr -dc '0-9' <"$file" 2>/dev/null) || return 1
    [[ -n $pid ]] || return 1
    comm=$(cat "/proc/$pid/comm" 2>/dev/null) || return 1
    [[ $comm == "$name" ]] || return 1
    is_alive "$pid" || return 1
    printf '%s\n' "$pid"
}

# stop_pids PID...: SIGTERM, wait up to STOP_TIMEOUT seconds, then SIGKILL.
stop_pids() {
    (($# > 0)) || return 0
    local pid i alive
    kill -TERM "$@" 2>/dev/null || true
    for ((i = 0; i < STOP_TIMEOUT * 10; i++)); do
        alive=0
        for pid in "$@"; do
            if is_alive "$pid"; then alive=1; fi
        done
        ((alive)) || return 0
        sleep 0.1
    done
    kill -KILL "$@" 2>/dev/null || true
}

# Job steps (slurmstepd and the job's processes) outlive slurmd, so find the
# slurmstepd processes spawned by this cluster's slurmd (they inherit its
# SLURM_CONF) and everything below them.
stepd_tree_pids() {
    local p ppid env_file roots=()
    for env_file in /proc/[0-9]*/environ; do
        p=${env_file#/proc/}; p=${p%/environ}
        [[ $(cat "/proc/$p/comm" 2>/dev/null) == slurmstepd ]] || continue
        if { tr '\0' '\n' <"$env_file"; } 2>/dev/null | grep -qxF "SLURM_CONF=$CONF"; then
            roots+=("$p")
        fi
    done
    ((${#roots[@]} > 0)) || return 0
    # Walk the parent links of all processes to collect the descendants.
    local -A parent=()
    local stat rest
    for stat in /proc/[0-9]*/stat; do
        p=${stat#/proc/}; p=${p%/stat}
        rest=$(cat "$stat" 2>/dev/null) || continue
        rest=${rest##*) }            # drop "pid (comm) "; comm may hold spaces
        read -r _ ppid _ <<<"$rest"
        parent[$p]=$ppid
    done
    local -A in_tree=()
    for p in "${roots[@]}"; do in_tree[$p]=1; done
    local changed=1
    while ((changed)); do
        changed=0
        for p in "${!parent[@]}"; do
            if [[ -z ${in_tree[$p]:-} && -n ${in_tree[${parent[$p]}]:-} ]]; then
                in_tree[$p]=1; changed=1
            fi
        done
    done
    printf '%s\n' "${!in_tree[@]}"
}

stop_cluster() {
    # Cancel jobs while slurmctld is still there so they end cleanly (they
    # get SIGTERM, then SIGKILL after KillWait); give that up to ~10 s.
    if pid_of "$CTLD_PID" slurmctld >/dev/null && [[ -r $CONF ]] &&
        SLURM_CONF=$CONF timeout 5 scancel --quiet --partition="$PARTITION" >/dev/null 2>&1; then
        local deadline=$((SECONDS + 10))
        while ((SECONDS < deadline)); do
            [[ -z $(SLURM_CONF=$CONF timeout 5 squeue -h -o %i 2>/dev/null) ]] && break
            sleep 0.2
        done
    fi
    # Each daemon takes 1-2 s to exit on SIGTERM and none needs the others
    # to shut down, so stop them together.
    local -a pids=()
    local pid
    if pid=$(pid_of "$SLURMD_PID" slurmd); then pids+=("$pid"); fi
    if pid=$(pid_of "$CTLD_PID" slurmctld); then pids+=("$pid"); fi
    if pid=$(pid_of "$MUNGE_PID" munged); then pids+=("$pid"); fi
    stop_pids "${pids[@]}"
    rm -f "$SLURMD_PID" "$CTLD_PID" "$MUNGE_PID"
    # Steps left behind (slurmctld was gone, so no scancel) are orphans now;
    # slurmstepd ignores SIGTERM, so kill them and their jobs outright.
    local -a left=()
    mapfile -t left < <(stepd_tree_pids)
    if ((${#left[@]} > 0)); then kill -KILL "${left[@]}" 2>/dev/null || true; fi
}

# ------------------------------------------------------------------- up ----
UP_DONE=0
fail() { # fail REASON [LOGFILE...]
    local reason=$1 log
    shift
    UP_DONE=1 # the EXIT trap must not report a second time
    # Clean up first: the report below may hit a closed stderr (SIGPIPE).
    stop_cluster
    trap '' PIPE
    {
        echo "$PROG: cannot start a Slurm cluster here: $reason"
        for log in "$@"; do
            if [[ -s $log ]]; then
                echo "--- last lines of $log:"
                tail -n 20 "$log" | sed 's/^/    /'
            fi
        done
    } >&2 || true
    exit 3
}

# Any unexpected error (mkdir in a read-only DIR, ...) also means "Slurm
# cannot start here": report it as such and clean up.
on_up_exit() {
    local rc=$?
    if ((UP_DONE == 0)); then
        trap - EXIT
        echo "$PROG: cannot start a Slurm cluster here: unexpected failure (exit $rc) at line ${ERR_LINE:-?}: ${ERR_CMD:-?}" >&2
        stop_cluster
        exit 3
    fi
}

# Two distinct unused TCP ports (held open together so they differ).
free_ports() {
    if command -v python3 >/dev/null; then
        python3 - <<'EOF'
import socket
socks = [socket.socket(socket.AF_INET, socket.SOCK_STREAM) for _ in range(2)]
for s in socks:
    s.bind(("", 0))
print(*(s.getsockname()[1] for s in socks))
EOF
        return
    fi
    # Fallback: random ports not listed as in use in /proc/net/tcp{,6}.
    local used="" ports=() p hex
    while read -r hex; do
        if [[ $hex =~ ^[0-9A-Fa-f]+$ ]]; then used+="$((16#$hex))"$'\n'; fi
    done < <(awk 'FNR > 1 { split($2, a, ":"); print a[2] }' /proc/net/tcp /proc/net/tcp6 2>/dev/null)
    while ((${#ports[@]} < 2)); do
        p=$((20000 + RANDOM % 40000))
        grep -qx "$p" <<<"$used" || [[ " ${ports[*]} " == *" $p "* ]] || ports+=("$p")
    done
    echo "${ports[@]}"
}

gpu_devices() {
    # Only when the driver sees GPUs; list their device files for gres.conf.
    command -v nvidia-smi >/dev/null || return 0
    local n
    n=$(timeout 20 nvidia-smi -L 2>/dev/null | grep -c '^GPU ') || return 0
    ((n > 0)) || return 0
    find /dev -maxdepth 1 -name 'nvidia[0-9]*' 2>/dev/null | sort -V | head -n "$n"
}

write_conf() {
    local ctld_port=$1 slurmd_port=$2 cpus mem_mb gres_line=""
    cpus=$(nproc)
    # RealMemory must not exceed what slurmd measures or the node is drained.
    mem_mb=$(awk '/^MemTotal:/ { print int($2 / 1024 * 0.95) }' /proc/meminfo)
    ((mem_mb > 0)) || mem_mb=1

    local -a gpus=()
    mapfile -t gpus < <(gpu_devices)
    rm -f "$GRES_CONF"
    if ((${#gpus[@]} > 0)); then
        gres_line=" Gres=gpu:${#gpus[@]}"
        {
            echo "# Generated by $0 from nvidia-smi -L."
            local g
            for g in "${gpus[@]}"; do echo "NodeName=$NODE Name=gpu File=$g"; done
        } >"$GRES_CONF"
    fi

    # An empty plugstack.conf keeps a system Slurm's SPANK plugins out.
    : >"$PLUGSTACK"

    cat >"$CONF" <<EOF
# Generated by $0 up $DIR -- a throw-away one-host cluster.
ClusterName=$CLUSTER
SlurmctldHost=$NODE(127.0.0.1)
# Ports picked free at 'up' time so several clusters (or a system Slurm) coexist.
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
# cred_expire (default 120 s, minimum 5) is also how long a requeued job
# waits (BeginTime) before it may start again; tests requeue.
AuthInfo=socket=$MUNGE_SOCKET,cred_expire=10
CredType=cred/munge
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
PlugStackConfig=$PLUGSTACK
MailProg=/bin/true
# One CPU per array task, so array elements run side by side.
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
# Trust this file over the hardware probe (containers report odd values).
SlurmdParameters=config_overrides
# Without these a job whose BeginTime passed (e.g. a requeued one) waits for
# the next backfill (30 s) or main (60 s) scheduling pass.
SchedulerParameters=bf_interval=1,sched_interval=1
ReturnToService=2
# Short timeouts: tests want finished jobs gone and kills quick.
SlurmdTimeout=10
SlurmctldTimeout=10
MinJobAge=2
KillWait=2
InactiveLimit=0
Waittime=0
StateSaveLocation=$STATE_DIR
SlurmdSpoolDir=$SPOOL_DIR
SlurmctldPidFile=$CTLD_PID
SlurmdPidFile=$SLURMD_PID
SlurmctldLogFile=$CTLD_LOG
SlurmdLogFile=$SLURMD_LOG
SlurmctldDebug=info
SlurmdDebug=info
${gres_line:+GresTypes=gpu}
# Every CPU is declared a core: with CR_Core a 1-CPU task then takes one CPU,
# not a whole hyperthreaded core.
NodeName=$NODE NodeAddr=127.0.0.1 CPUs=$cpus Sockets=1 CoresPerSocket=$cpus ThreadsPerCore=1 RealMemory=$mem_mb$gres_line State=UNKNOWN
PartitionName=$PARTITION Nodes=$NODE Default=YES MaxTime=INFINITE State=UP
EOF
}

start_munged() {
    rm -f "$MUNGE_KEY"
    # mungekey writes a proper key; dd is the documented fallback.
    if command -v mungekey >/dev/null; then
        mungekey --create --keyfile="$MUNGE_KEY" >/dev/null 2>&1 ||
            dd if=/dev/urandom of="$MUNGE_KEY" bs=1 count=1024 status=none
    else
        dd if=/dev/urandom of="$MUNGE_KEY" bs=1 count=1024 status=none
    fi
    chmod 0400 "$MUNGE_KEY"
    rm -f "$MUNGE_SOCKET" "$MUNGE_SOCKET.lock" "$MUNGE_PID"
    local -a args=(--socket="$MUNGE_SOCKET" --key-file="$MUNGE_KEY"
        --pid-file="$MUNGE_PID" --log-file="$MUNGE_LOG" --seed-file="$MUNGE_SEED")
    # munged refuses e.g. a socket directory that is not world-accessible
    # (mktemp -d gives 0700); everything here runs as root, so --force is fine.
    if ! munged "${args[@]}" </dev/null >"$DIR/log/munged.stderr" 2>&1 &&
        ! munged --force "${args[@]}" </dev/null >>"$DIR/log/munged.stderr" 2>&1; then
        fail "munged did not start" "$DIR/log/munged.stderr" "$MUNGE_LOG"
    fi
    local i
    for ((i = 0; i < 50; i++)); do
        [[ -S $MUNGE_SOCKET ]] && pid_of "$MUNGE_PID" munged >/dev/null && break
        sleep 0.1
    done
    [[ -S $MUNGE_SOCKET ]] || fail "munged did not create $MUNGE_SOCKET" "$DIR/log/munged.stderr" "$MUNGE_LOG"
    if command -v munge >/dev/null && command -v unmunge >/dev/null; then
        munge -n -S "$MUNGE_SOCKET" 2>/dev/null | unmunge -S "$MUNGE_SOCKET" >/dev/null 2>&1 ||
            fail "munge credentials do not round-trip through $MUNGE_SOCKET" "$MUNGE_LOG"
    fi
}

# start_daemon NAME PIDFILE ARGS...
start_daemon() {
    local name=$1 pidfile=$2 pid i
    shift 2
    rm -f "$pidfile"
    # Run in the foreground (-D) as our background child, so that a daemon
    # dying during start-up is noticed at once rather than after a timeout;
    # setsid detaches it from our terminal/session. stdin/stdout/stderr are
    # redirected so that $(...) around 'up' does not wait on a pipe the
    # daemon holds open.
    local -a detach=()
    if command -v setsid >/dev/null; then detach=(setsid); fi
    (cd "$DIR" && SLURM_CONF=$CONF exec "${detach[@]}" "$name" -D "$@") \
        </dev/null >"$DIR/log/$name.stderr" 2>&1 &
    pid=$!
    for ((i = 0; i < 100; i++)); do
        # (With -D the daemon logs to stderr as well as to its log file.)
        is_alive "$pid" || fail "$name exited during start-up" "$DIR/log/$name.stderr"
        [[ $(pid_of "$pidfile" "$name" || true) == "$pid" ]] && return 0
        sleep 0.1
    done
    fail "$name did not write $pidfile" "$DIR/log/$name.stderr"
}

cmd_up() {
    set_paths "$1"
    set -o errtrace # so the ERR trap also sees failures inside functions
    trap 'ERR_LINE=$LINENO ERR_CMD=$BASH_COMMAND' ERR
    trap on_up_exit EXIT
    trap 'UP_DONE=1; stop_cluster; exit 130' INT TERM

    [[ $(id -u) == 0 ]] || fail "must run as root (slurmd launches jobs as their owner)"
    local b
    for b in munged slurmctld slurmd sinfo sbatch scontrol squeue scancel; do
        command -v "$b" >/dev/null ||
            fail "$b not found (Debian: apt-get install slurm-wlm munge)"
    done

    local err
    err=$(mkdir -p "$DIR" "$DIR/log" "$DIR/run" "$STATE_DIR" "$SPOOL_DIR" "$MUNGE_DIR" 2>&1) ||
        fail "cannot create directories in $DIR: ${err%%$'\n'*}"
    chmod 0700 "$MUNGE_DIR" # munged wants its key directory private
    # Fresh logs, so a failure report shows this attempt only.
    rm -f "$DIR"/log/*.log "$DIR"/log/*.stderr
    # A previous 'up DIR' that was never taken down must not linger.
    stop_cluster

    local ctld_port slurmd_port
    read -r ctld_port slurmd_port <<<"$(free_ports)"
    write_conf "$ctld_port" "$slurmd_port"
    start_munged
    # -c: start from empty job/node state even if DIR was used before.
    start_daemon slurmctld "$CTLD_PID" -c
    start_daemon slurmd "$SLURMD_PID" -N "$NODE"

    local deadline=$((SECONDS + UP_TIMEOUT)) state="" why
    while :; do
        pid_of "$CTLD_PID" slurmctld >/dev/null || fail "slurmctld died" "$CTLD_LOG"
        pid_of "$SLURMD_PID" slurmd >/dev/null || fail "slurmd died" "$SLURMD_LOG"
        state=$(SLURM_CONF=$CONF timeout 5 sinfo -h -o %T 2>&1 || true)
        [[ $state == idle ]] && break
        ((SECONDS < deadline)) || break
        sleep 0.2
    done
    if [[ $state != idle ]]; then
        why=$(SLURM_CONF=$CONF timeout 5 scontrol show node "$NODE" 2>/dev/null | grep -o 'Reason=.*' || true)
        fail "node $NODE not idle after ${UP_TIMEOUT}s (sinfo: '${state//$'\n'/ }'${why:+, $why})" "$CTLD_LOG" "$SLURMD_LOG"
    fi

    UP_DONE=1
    echo "export SLURM_CONF=$CONF"
}

cmd_down() {
    set_paths "$1"
    [[ -d $DIR ]] || return 0
    stop_cluster
}

main() {
    case ${1:-} in
    -h | --help | help) usage ;;
    up | down)
        (($# == 2)) || die_usage "'$1' takes exactly one argument, DIR"
        local dir
        dir=$(check_dir_arg "$2") || exit 2
        "cmd_$1" "$dir"
        ;;
    "") usage >&2; exit 2 ;;
    *) die_usage "unknown command: $1" ;;
    esac
}

# Run unless sourced (tests may source it to reach the functions).
if [[ ${BASH_SOURCE[0]} == "$0" ]]; then main "$@"; fi
