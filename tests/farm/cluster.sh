# A single-node Slurm cluster for the farm tests, in a temporary folder: munged, slurmctld and
# slurmd started there with their own socket, ports and state, and stopped by pid.
#
#   source tests/farm/cluster.sh; start_cluster; …; stop_cluster
# start_cluster sets `work` (a temporary folder, removed by stop_cluster) and exports SLURM_CONF.

# The teapot turntable shot with the files it reads, copied into the folder $1 (from $root).
copy_turntable() {
    mkdir -p "$1/shots/looks" "$1/patches"
    cp "$root/shots/teapot_turntable.ron" "$1/shots/"
    cp "$root/shots/looks/studio.ron" "$1/shots/looks/"
    cp "$root/patches/teapot.bpt" "$root/patches/teapot.parts.ron" "$1/patches/"
}

# Whether the jobs $1 (a comma-separated list) have all left the queue: squeue answered and
# listed none of them, on each of 10 readings 0.1 s apart. A reading where squeue does not
# answer (the controller busy) counts as not yet, and so does a single empty one: a task that
# requeues itself can be missing from the list between its end and its new start.
queue_empty() {
    local listed
    for _ in $(seq 10); do
        listed="$(squeue -h -j "$1" 2>/dev/null)" || return 1
        [ -z "$listed" ] || return 1
        sleep 0.1
    done
}

# Lets the requeued job $1 (its own id: `squeue -o %A`) start again at once rather than wait out
# Slurm's requeue delay, once its earlier try has left the node (no slurmstepd of it runs) and
# two seconds have passed since the requeue; answers 1 until then. A try launched sooner fails
# at once with no output — slurmd refuses a credential issued in the second its job's last one
# was revoked ("Job credential revoked") — which the delay a real farm keeps never lets happen.
release_requeued_job() {
    pgrep -f "slurmstepd: \[$1\." >/dev/null && return 1
    local requeued
    requeued="$(scontrol show job "$1" 2>/dev/null | sed -n 's/.*SubmitTime=\([^ ]*\).*/\1/p' | head -n 1)"
    [ -n "$requeued" ] || return 1
    [ $(($(date +%s) - $(date -d "$requeued" +%s))) -ge 2 ] || return 1
    scontrol update JobId="$1" StartTime=now >/dev/null 2>&1 || true
}

# What Slurm's own daemons said last, for a failure message.
slurm_logs() {
    tail -n 30 "$cluster/log/slurmctld.log" "$cluster/log/slurmd.log" 2>/dev/null || true
}

require_slurm() {
    for tool in munged slurmctld slurmd sbatch squeue scontrol sinfo; do
        command -v "$tool" >/dev/null || { echo "$tool is missing: apt-get install slurm-wlm munge" >&2; exit 2; }
    done
}

stop_cluster() {
    for daemon in slurmd slurmctld munged; do
        if [ -f "$cluster/$daemon.pid" ]; then
            kill "$(cat "$cluster/$daemon.pid")" 2>/dev/null || true
        fi
    done
    sleep 1
    rm -rf "$work"
}

start_cluster() {
    require_slurm
    work="$(mktemp -d)"
    cluster="$work/cluster"
    mkdir -p "$cluster/state" "$cluster/spool" "$cluster/log"

    host="$(hostname)"
    port=$((20000 + RANDOM % 20000))
    head -c 1024 /dev/urandom > "$cluster/munge.key"
    chmod 600 "$cluster/munge.key"
    munged -S "$cluster/munge.socket" --key-file "$cluster/munge.key" --pid-file "$cluster/munged.pid" \
        --log-file "$cluster/log/munged.log" --seed-file "$cluster/munge.seed" -f
    cat > "$cluster/slurm.conf" <<CONF
ClusterName=glinttest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$cluster/munge.socket
CredType=cred/munge
SlurmUser=$(id -un)
SlurmdUser=$(id -un)
StateSaveLocation=$cluster/state
SlurmdSpoolDir=$cluster/spool
SlurmctldPidFile=$cluster/slurmctld.pid
SlurmdPidFile=$cluster/slurmd.pid
SlurmctldLogFile=$cluster/log/slurmctld.log
SlurmdLogFile=$cluster/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU_Memory
JobRequeue=1
ReturnToService=2
MpiDefault=none
SwitchType=switch/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=4000 State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
    export SLURM_CONF="$cluster/slurm.conf"
    slurmctld -f "$SLURM_CONF"
    slurmd -f "$SLURM_CONF"
    for _ in $(seq 100); do
        sinfo -h -o %T 2>/dev/null | grep -q idle && break
        sleep 0.2
    done
    sinfo -h -o %T | grep -q idle || { echo "the cluster did not come up" >&2; cat "$cluster/log/"*.log >&2; exit 1; }
}
