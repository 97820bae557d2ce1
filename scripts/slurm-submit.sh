#!/bin/bash
# Runs a loomkin sweep, table or Monte-Carlo study as a Slurm job array of SHARDS tasks (default 16),
# then a merge job once every task has succeeded:
#
#   scripts/slurm-submit.sh OUTPUT LOOMKIN-ARGS...
#   SHARDS=64 scripts/slurm-submit.sh speed.csv pick sweep speed --from 160 --to 240 --points 1000000 --csv
#   scripts/slurm-submit.sh draws.csv pick montecarlo examples/pick-montecarlo.toml --csv
#
# The merge concatenates shards/part-* in order into OUTPUT (the one-machine output, byte for byte)
# and checks that every part is there. For a Monte-Carlo study, the report then comes from
#   loomkin pick montecarlo STUDY.toml --from-draws OUTPUT --json
set -euo pipefail

if [ "$#" -lt 2 ]; then
    echo "usage: $0 OUTPUT LOOMKIN-ARGS... (with --csv or --json)" >&2
    exit 2
fi
output=$1
shift
shards=${SHARDS:-16}
here=$(dirname "$0")
mkdir -p shards
rm -f shards/part-*

array=$(sbatch --parsable --array="1-$shards" "$here/slurm-shards.sbatch" "$@")
merge="n=\$(ls shards/part-* | wc -l); [ \"\$n\" -eq $shards ] || { echo \"\$n of $shards parts\" >&2; exit 1; }; \
cat shards/part-* > '$output'"
sbatch --parsable --job-name=loomkin-merge --dependency="afterok:$array" --output=shards/merge-%j.log \
    --wrap="$merge"
echo "submitted array $array ($shards shards) and its merge into $output"
