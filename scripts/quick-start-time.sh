#!/bin/bash
# Times the README's quick start as a new user runs it: a fresh clone of this repository, an empty cargo
# home (every crate downloaded), the README's commands exactly as printed. Run it on an idle machine,
# in the foreground: a shell's background job ignores SIGINT, and the Python package's Ctrl-C tests then
# fail. Needs curl and bc; port 8765 free.
#   scripts/quick-start-time.sh <label>      # logs in /tmp/qs-<label>-out/log
set -u
L=${1:-run}; SRC=$(cd "$(dirname "$0")/.." && pwd)
D=/tmp/qs-$L; OUT=/tmp/qs-$L-out; CH=/tmp/qs-$L-cargo
rm -rf $D $CH $OUT; mkdir -p $OUT $CH
git clone -q "$SRC" $D || exit 1
cd $D; git log --oneline -1 > $OUT/commit
unset CARGO_TARGET_DIR RUSTFLAGS CARGO_INCREMENTAL; export CARGO_HOME=$CH
echo "start $(date -u +%T) load $(cut -d' ' -f1-3 /proc/loadavg)" > $OUT/log
T0=$(date +%s.%N)
( /usr/bin/time -f "%e s wall %U user %S sys" -o $OUT/t-serve cargo run --release -p loomkin-cli -- serve --open > $OUT/serve.out 2>&1 ) &
job=$!
until curl -s -o /dev/null http://127.0.0.1:8765/; do
  kill -0 $job 2>/dev/null || { echo "the serve command ended without serving: $OUT/serve.out" >&2; exit 1; }
  sleep 0.5
done
T1=$(date +%s.%N)
echo "serve answered $(date -u +%T) after $(echo "$T1-$T0" | bc) s load $(cut -d' ' -f1-3 /proc/loadavg)" >> $OUT/log
pkill -INT -f "target/release/loomkin serve"; wait $job
# CPU of the serve step up to here (the server idles after it answered)
cat $OUT/t-serve >> $OUT/log
T2=$(date +%s.%N)
/usr/bin/time -f "%e s wall %U user %S sys" -o $OUT/t-test cargo test --release --workspace > $OUT/test.out 2>&1
rc=$?
T3=$(date +%s.%N)
echo "test done rc=$rc $(date -u +%T) after $(echo "$T3-$T2" | bc) s; both: $(echo "$T1-$T0+$T3-$T2" | bc) s load $(cut -d' ' -f1-3 /proc/loadavg)" >> $OUT/log
cat $OUT/t-test >> $OUT/log
/usr/bin/time -f "%e s wall %U user %S sys" -o $OUT/t-py bash python/test.sh > $OUT/py.out 2>&1
echo "python rc=$? $(date -u +%T) $(cat $OUT/t-py)" >> $OUT/log
cat $OUT/log
