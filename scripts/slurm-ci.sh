#!/bin/bash
# docs/scale.md's Slurm recipe end to end on a single-node Slurm brought up here (Debian's
# slurm-wlm and munge; installed when missing and apt-get is there): a sweep as a job array, a lost
# part found by `loomkin merge` and rerun alone with `sbatch --array=3`, the merge, a Pareto reduce
# of a sharded table and a Monte-Carlo reduce of sharded draws, each compared byte for byte with
# the one-machine run. Sizes: 1001 sweep points in 7 shards, a 36-law table at 5 angles in 3
# shards, 2000 draws in 4 shards. When Slurm cannot be installed or started, it says so and exits 0.
# Measured on the reference machine: install 63 s, daemons up in 3 s, the runs 1 min.
set -uo pipefail
cd "$(dirname "$0")/.."
repo=$(pwd)
export LOOMKIN=${LOOMKIN:-$repo/target/release/loomkin}
skip() { echo "slurm-ci: SKIPPED: $*"; exit 0; }
fail() { echo "slurm-ci: FAILED: $*"; exit 1; }
[ -x "$LOOMKIN" ] || fail "no loomkin binary at $LOOMKIN (build first)"
if ! command -v slurmctld >/dev/null 2>&1 || ! command -v munged >/dev/null 2>&1; then
    command -v apt-get >/dev/null 2>&1 || skip "slurm-wlm is not installed and there is no apt-get"
    (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge >/dev/null 2>&1) \
        || skip "could not install slurm-wlm and munge"
fi
[ "$(id -u)" -eq 0 ] || skip "starting slurmctld and slurmd needs root"
pids=()
stop() { for f in "${pids[@]}"; do [ -f "$f" ] && kill "$(cat "$f")" 2>/dev/null; done; }
trap stop EXIT
if ! sinfo -h >/dev/null 2>&1; then
    host=$(hostname -s)
    [ -f /etc/munge/munge.key ] || { dd if=/dev/urandom bs=1 count=1024 of=/etc/munge/munge.key 2>/dev/null; chown munge:munge /etc/munge/munge.key; chmod 400 /etc/munge/munge.key; }
    mkdir -p /run/munge /var/spool/slurmctld /var/spool/slurmd /var/log/slurm /etc/slurm
    chown munge:munge /run/munge
    cpus=$(nproc)
    cat > /etc/slurm/slurm.conf <<CONF
ClusterName=loomkin-ci
SlurmctldHost=$host
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
SlurmctldPidFile=/run/slurmctld.pid
SlurmdPidFile=/run/slurmd.pid
SlurmdSpoolDir=/var/spool/slurmd
StateSaveLocation=/var/spool/slurmctld
SlurmUser=root
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
    runuser -u munge -- /usr/sbin/munged || skip "munged did not start"
    pids+=(/run/munge/munged.pid)
    /usr/sbin/slurmctld || skip "slurmctld did not start"
    pids+=(/run/slurmctld.pid)
    /usr/sbin/slurmd || skip "slurmd did not start"
    pids+=(/run/slurmd.pid)
    for _ in $(seq 1 30); do sinfo -h -t idle 2>/dev/null | grep -q . && break; sleep 1; done
    sinfo -h -t idle | grep -q . || skip "the node did not come up idle: $(sinfo 2>&1 | tail -1)"
fi
work=$(mktemp -d)
cd "$work" || fail "no scratch directory"
wait_all() { for _ in $(seq 1 600); do [ -z "$(squeue -h 2>/dev/null)" ] && return 0; sleep 1; done; fail "jobs still queued after 10 min"; }
same() { cmp -s "$1" "$2" && echo "slurm-ci: $3: identical to the one-machine run" || fail "$3: $1 differs from $2"; }

# 1. A sweep in 7 shards; then a lost part (a task killed before its rename leaves none), found by
#    the merge and rerun alone: exactly part 3 is remade.
sweep=(pick sweep speed --from 160 --to 240 --points 1001 --csv)
"$LOOMKIN" "${sweep[@]}" > sweep-whole.csv
bash "$repo/scripts/slurm-submit.sh" -n 7 -t 00:05:00 sweep sweep.csv "${sweep[@]}" || fail "submit"
wait_all
same sweep.csv sweep-whole.csv "sweep, 7 shards"
rm sweep/parts/part-00003-of-00007.csv sweep/parts/part-00003-of-00007.csv.manifest.json
out=$("$LOOMKIN" merge sweep/parts -o again.csv 2>&1) && fail "merge accepted a missing part"
echo "slurm-ci: merge refused as it should: $out"
echo "$out" | grep -q "shard 3 (rerun: sbatch --array=3" || fail "the merge did not name shard 3"
timeout 600 sbatch --parsable --wait --array=3 --output=sweep/logs/rerun-%A_%a.log "$repo/scripts/slurm-shards.sbatch" 7 sweep "${sweep[@]}" >/dev/null \
    || fail "rerun of task 3"
"$LOOMKIN" merge sweep/parts -o again.csv || fail "merge after the rerun"
same again.csv sweep-whole.csv "sweep after rerunning part 3"

# 2. A table in 3 shards and its Pareto front by the reduce.
table=(shed table --design grid --step 0.1 --motion-deg 200:360:40 --csv)
bash "$repo/scripts/slurm-submit.sh" -n 3 table table.csv "${table[@]}" || fail "submit table"
# 3. Draws in 4 shards and the report from the parts.
study=$repo/examples/pick-montecarlo.toml
bash "$repo/scripts/slurm-submit.sh" -n 4 mc draws.csv pick montecarlo "$study" --csv || fail "submit draws"
wait_all
"$LOOMKIN" shed pareto --from table/parts --csv > front.csv || fail "pareto reduce"
"$LOOMKIN" shed pareto --design grid --step 0.1 --motion-deg 200:360:40 --csv > front-whole.csv
same front.csv front-whole.csv "Pareto front from 3 shards"
"$LOOMKIN" pick montecarlo "$study" --json --from-draws mc/parts > report.json || fail "Monte-Carlo reduce"
"$LOOMKIN" pick montecarlo "$study" --json > report-whole.json
same report.json report-whole.json "Monte-Carlo report from 4 shards"
cd / && rm -rf "$work"
echo "slurm-ci: passed"
