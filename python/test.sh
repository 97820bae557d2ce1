#!/usr/bin/env bash
# The Python package's tests: builds `loomkin` (release, abi3 wheel) into a virtual environment
# with `pip install ./python[test]` (pytest, pandas, matplotlib, dask[distributed], mypy), then runs
# pytest and mypy's stubtest. The parity tests run the CLI binary
# (<target>/release/loomkin, which `cargo test --release --workspace` has built; built here if
# missing; $LOOMKIN_BIN names another). The venv: $LOOMKIN_VENV, default <target>/python-venv.
set -euo pipefail
cd "$(dirname "$0")/.."
target="${CARGO_TARGET_DIR:-$PWD/target}"
venv="${LOOMKIN_VENV:-$target/python-venv}"
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/pip" install -q "./python[test]"
bin="${LOOMKIN_BIN:-$target/release/loomkin}"
[ -x "$bin" ] || cargo build --release -p loomkin-cli
cd python
# `pytest`, not `python -m pytest`: the latter puts python/ on sys.path, where the sources of the
# package (without its compiled module) would shadow the installed package.
LOOMKIN_BIN="$bin" "$venv/bin/pytest" -q tests
# The type stubs (loomkin/_loomkin.pyi) against the compiled module, and the package's own types
# (mypy): run from the venv so that the installed package, not these sources, is imported.
(cd "$venv" && "$venv/bin/python" -m mypy.stubtest loomkin --concise --mypy-config-file "$OLDPWD/pyproject.toml")
echo "stubtest: loomkin's stubs match the compiled module"
