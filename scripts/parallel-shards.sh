#!/bin/bash
# The same sharded run on one workstation with GNU parallel: SHARDS single-threaded shards
# (default: one per CPU), their outputs printed in shard order (--keep-order), so standard output
# is byte for byte the one-machine output.
#
#   scripts/parallel-shards.sh pick sweep speed --from 160 --to 240 --points 100000 --csv > speed.csv
#   SHARDS=8 scripts/parallel-shards.sh pick montecarlo examples/pick-montecarlo.toml --csv > draws.csv
#   loomkin pick montecarlo examples/pick-montecarlo.toml --from-draws draws.csv
#
# (loomkin alone already uses every CPU through rayon; shards pay off when a run is split across
# machines, or to restart only the shards that failed: each is `loomkin ARGS --shard I/N`.)
set -euo pipefail

if [ "$#" -eq 0 ]; then
    echo "usage: $0 LOOMKIN-ARGS... (with --csv or --json)" >&2
    exit 2
fi
shards=${SHARDS:-$(nproc)}
args=$(printf '%q ' "$@")
seq 1 "$shards" | RAYON_NUM_THREADS=1 parallel --jobs "$shards" --keep-order --halt now,fail=1 \
    "loomkin $args --shard {}/$shards"
