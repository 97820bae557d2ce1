#!/bin/bash
# Runs a loomkin sweep, table or Monte-Carlo study as Slurm job arrays of N tasks, then a merge job
# that checks the parts and writes the one-machine output (docs/scale.md):
#
#   scripts/slurm-submit.sh [OPTIONS] STUDY_DIR OUTPUT LOOMKIN-ARGS...
#   scripts/slurm-submit.sh -n 64 -c 4 --mem 2G -t 00:30:00 runs/speed speed.csv \
#       pick sweep speed --from 160 --to 240 --points 10000000 --csv
#
# Options (each also as an environment variable):
#   -n, --shards N      number of shards (SHARDS, default 16)
#   -c, --cpus C        CPUs per task (CPUS, default 1)
#   --mem M             memory per task, as sbatch takes it (MEM)
#   -t, --time T        time limit per task (TIME)
#   -p, --partition P   partition (PARTITION)
#   --throttle K        at most K tasks of an array at once (sbatch --array=…%K) (THROTTLE)
#   --max-array M       Slurm's MaxArraySize (MAX_ARRAY; default: read from scontrol, else 1001):
#                       past it the shards go in several arrays
#   --sbatch OPT        any other sbatch option, repeatable
#
# STUDY_DIR holds this study only: parts/ (the parts and their manifests) and logs/ (made here,
# before submission). The merge job waits for every task to end, failed or not
# (--dependency=afterany), then `loomkin merge` checks that all N parts are there and whole: it
# writes OUTPUT, or fails naming the shards to rerun (`sbatch --array=LIST …`, as printed below).
set -euo pipefail

shards=${SHARDS:-16}
cpus=${CPUS:-1}
mem=${MEM:-}
time=${TIME:-}
partition=${PARTITION:-}
throttle=${THROTTLE:-}
max_array=${MAX_ARRAY:-}
extra=()
usage() {
    echo "usage: $0 [-n N] [-c CPUS] [--mem M] [-t TIME] [-p PARTITION] [--throttle K] [--max-array M] [--sbatch OPT]... STUDY_DIR OUTPUT LOOMKIN-ARGS..." >&2
    exit 2
}
while [ "$#" -gt 0 ]; do
    case "$1" in
    -n | --shards) shards=$2; shift 2 ;;
    -c | --cpus) cpus=$2; shift 2 ;;
    --mem) mem=$2; shift 2 ;;
    -t | --time) time=$2; shift 2 ;;
    -p | --partition) partition=$2; shift 2 ;;
    --throttle) throttle=$2; shift 2 ;;
    --max-array) max_array=$2; shift 2 ;;
    --sbatch) extra+=("$2"); shift 2 ;;
    -h | --help) usage ;;
    -*) echo "$0: unknown option $1" >&2; usage ;;
    *) break ;;
    esac
done
[ "$#" -ge 3 ] || usage
dir=$1
output=$2
shift 2
case "$shards" in '' | *[!0-9]* | 0) echo "$0: --shards '$shards' is not a number ≥ 1" >&2; exit 2 ;; esac
sbatch=${SBATCH:-sbatch}
here=$(cd "$(dirname "$0")" && pwd)
if [ -z "$max_array" ]; then
    max_array=$(scontrol show config 2>/dev/null | awk '/^MaxArraySize/ {print $3}')
    max_array=${max_array:-1001}
fi
# Array indices run from 0 to MaxArraySize − 1: each array takes shards 1…(MaxArraySize − 1) of its block.
per_array=$((max_array - 1))
mkdir -p "$dir/logs" "$dir/parts"

opts=(--parsable --cpus-per-task="$cpus" --output="$dir/logs/shard-%A_%a.log")
[ -n "$mem" ] && opts+=(--mem="$mem")
[ -n "$time" ] && opts+=(--time="$time")
[ -n "$partition" ] && opts+=(--partition="$partition")
opts+=(${extra[@]+"${extra[@]}"})

jobs=()
offset=0
while [ "$offset" -lt "$shards" ]; do
    n=$((shards - offset))
    [ "$n" -gt "$per_array" ] && n=$per_array
    spec="1-$n${throttle:+%$throttle}"
    id=$("$sbatch" "${opts[@]}" --export=ALL,LOOMKIN_SHARD_OFFSET="$offset" \
        --array="$spec" "$here/slurm-shards.sbatch" "$shards" "$dir" "$@")
    id=${id%%;*}
    jobs+=("$id")
    echo "array $id: shards $((offset + 1))-$((offset + n)) of $shards (offset $offset; rerun shard S of it: $sbatch --array=\$((S - $offset)) --export=ALL,LOOMKIN_SHARD_OFFSET=$offset … $here/slurm-shards.sbatch $shards $dir ARGS)"
    offset=$((offset + n))
done
deps=$(IFS=:; echo "${jobs[*]}")
merge=$(printf '%q merge %q -o %q' "${LOOMKIN:-loomkin}" "$dir/parts" "$output")
mid=$("$sbatch" --parsable --job-name=loomkin-merge --dependency="afterany:$deps" --kill-on-invalid-dep=yes \
    --output="$dir/logs/merge-%j.log" ${partition:+--partition="$partition"} --wrap="$merge")
echo "merge $mid: $merge, once every task has ended (log: $dir/logs/merge-${mid%%;*}.log)"
