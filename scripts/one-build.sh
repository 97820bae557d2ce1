#!/usr/bin/env bash
# Checks README's promise that its two commands share one build: after
#     cargo build --release -p loomkin-cli          (what `cargo run --release -p loomkin-cli` builds)
#     cargo test --release --workspace --no-run     (the test build)
# no crate that the first command compiled is compiled again by the second. Cargo names every
# compiled unit by a hash of its package, version, target, profile, features and dependencies; a
# crate asked for with other features (feature unification over the workspace and its
# dev-dependencies) gets another hash and is compiled a second time, and so is every crate above it.
# The check compares, unit by unit, the artifacts cargo reports for the two commands. It fails,
# naming each crate and both feature sets, when a unit of the first command appears in the second
# with another hash. The usual mend: `cargo hakari generate && cargo hakari manage-deps` (see
# crates/workspace-hack/Cargo.toml), which asks for the missing features in the workspace-hack.
# Works on a warm or an empty target directory (a unit already built is reported with its hash too).
# It also fails when a workspace member does not depend on the workspace-hack.
set -euo pipefail
cd "$(dirname "$0")/.."
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# Every member asks for the hack's features (else `cargo test -p <that crate>` alone recompiles shared
# crates with fewer features); a new crate without the line is named here.
cargo metadata --format-version 1 --no-deps | python3 -c '
import json, sys
hack = "loomkin-workspace-hack"
m = json.load(sys.stdin)
members = set(m["workspace_members"])
missing = [p["name"] for p in m["packages"] if p["id"] in members and p["name"] != hack
           and not any(d["name"] == hack and d["kind"] is None for d in p["dependencies"])]
if missing:
    sys.exit("one-build: " + ", ".join(sorted(missing)) + " do not depend on " + hack
             + ": run cargo hakari manage-deps (cargo install cargo-hakari --locked)")
'
cargo build --release -p loomkin-cli --message-format=json-render-diagnostics > "$out/run.jsonl"
cargo test --release --workspace --no-run --message-format=json-render-diagnostics > "$out/test.jsonl"
python3 - "$out/run.jsonl" "$out/test.jsonl" <<'PY'
import json, os, sys

def units(path):
    """(package id, target name, target kinds, test harness) -> {artifact file name: features}."""
    found = {}
    for line in open(path):
        try:
            m = json.loads(line)
        except ValueError:
            continue
        if m.get("reason") != "compiler-artifact":
            continue
        key = (m["package_id"], m["target"]["name"], tuple(m["target"]["kind"]), m["profile"]["test"])
        files = found.setdefault(key, {})
        for f in m["filenames"]:
            files[os.path.basename(f)] = (m["features"], m["fresh"])
    return found

def name(package_id):
    # "registry+https://…#serde@1.0.228" or "path+file:///…/crates/laws#loomkin-laws@0.1.0"
    tail = package_id.rsplit("#", 1)[-1]
    return tail if "@" in tail else package_id

run, test = units(sys.argv[1]), units(sys.argv[2])
twice = []
for key, files in sorted(test.items()):
    if key in run and not set(files) <= set(run[key]):
        features_run = sorted({tuple(f) for f, _ in run[key].values()})
        features_test = sorted({tuple(f) for f, _ in files.values()})
        twice.append((name(key[0]), key[1], key[2], features_run, features_test))
compiled = [k for k, files in test.items() if any(not fresh for _, fresh in files.values())]
print(f"one-build: {len(run)} units in the CLI build, {len(test)} in the test build, "
      f"{sum(1 for k in test if k in run)} shared; the test build compiled {len(compiled)} "
      f"(the rest it took from the first build or an earlier run)")
if twice:
    for crate, target, kind, fr, ft in twice:
        print(f"one-build: {crate} ({'/'.join(kind)} {target}) is compiled twice: "
              f"features {[list(f) for f in fr]} for the CLI, {[list(f) for f in ft]} for the tests",
              file=sys.stderr)
    print(f"one-build: {len(twice)} units compiled twice; regenerate the workspace-hack: "
          "cargo hakari generate && cargo hakari manage-deps (cargo install cargo-hakari --locked)",
          file=sys.stderr)
    sys.exit(1)
print("one-build: no unit of the CLI build is compiled again by the test build")
PY
