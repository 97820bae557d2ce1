"""Shared fixtures: the `loomkin` CLI binary, run from the repository root, for parity checks."""

from __future__ import annotations

import json
import math
import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


def _find_cli():
    env = os.environ.get("LOOMKIN_BIN")
    if env:
        return env
    target = pathlib.Path(os.environ.get("CARGO_TARGET_DIR") or REPO / "target")
    for profile in ("release", "debug"):
        p = target / profile / "loomkin"
        if p.exists():
            return str(p)
    return shutil.which("loomkin")


@pytest.fixture(scope="session")
def cli():
    """`cli(*args)` runs the loomkin binary from the repository root and returns its stdout parsed
    as JSON (or the text with `text=True`). The binary: $LOOMKIN_BIN, else target/{release,debug}
    under $CARGO_TARGET_DIR or ./target, else `loomkin` on PATH."""
    exe = _find_cli()
    if exe is None:
        pytest.fail("no loomkin binary: run `cargo build --release -p loomkin-cli` or set LOOMKIN_BIN")

    def run(*args, text=False):
        out = subprocess.run([exe, *map(str, args)], cwd=REPO, capture_output=True, text=True)
        assert out.returncode == 0, f"loomkin {' '.join(map(str, args))}: {out.stderr}"
        return out.stdout if text else json.loads(out.stdout)

    return run


def same(py, ref, path="$"):
    """Asserts that a Python result equals the CLI's JSON exactly: every number bit for bit (both
    sides print or hold the same f64), numpy arrays against lists, dicts key for key."""
    if isinstance(py, np.ndarray):
        py = py.tolist()
    if isinstance(ref, np.ndarray):
        ref = ref.tolist()
    if isinstance(py, dict):
        assert isinstance(ref, dict), f"{path}: dict vs {type(ref).__name__}"
        assert sorted(py) == sorted(ref), f"{path}: keys {sorted(py)} vs {sorted(ref)}"
        for k in py:
            same(py[k], ref[k], f"{path}.{k}")
    elif isinstance(py, (list, tuple)):
        assert isinstance(ref, list) and len(py) == len(ref), f"{path}: length {len(py)} vs {ref!r:.80}"
        for i, (a, b) in enumerate(zip(py, ref)):
            same(a, b, f"{path}[{i}]")
    elif isinstance(py, bool) or isinstance(ref, bool):
        assert py == ref, f"{path}: {py!r} vs {ref!r}"
    elif isinstance(py, (int, float)) and isinstance(ref, (int, float)):
        assert py == ref or (math.isnan(py) and math.isnan(ref)), f"{path}: {py!r} vs {ref!r}"
    else:
        assert py == ref, f"{path}: {py!r} vs {ref!r}"


def records(columns):
    """A dict of arrays as the CLI's list of records."""
    keys = list(columns)
    n = len(columns[keys[0]]) if keys else 0
    return [{k: (columns[k][i].item() if hasattr(columns[k][i], "item") else columns[k][i]) for k in keys}
            for i in range(n)]
