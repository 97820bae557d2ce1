"""docs/python.md works as printed: its Python cells run in order, as a notebook would, from a
directory with the repository's examples/, and write the figures they promise."""

import os
import re
import textwrap

import pytest

from conftest import REPO

DOC = REPO / "docs" / "python.md"


def cells():
    found = re.findall(r"```python\n(.*?)```", DOC.read_text(encoding="utf-8"), flags=re.S)
    return [textwrap.dedent(c) for c in found]


def test_the_worked_example_runs(tmp_path, monkeypatch):
    pytest.importorskip("matplotlib")
    (tmp_path / "examples").symlink_to(REPO / "examples")
    monkeypatch.chdir(tmp_path)
    namespace = {}
    code = cells()
    assert len(code) >= 7
    for i, cell in enumerate(code):
        exec(compile(cell, f"{DOC}:cell{i}", "exec"), namespace)
    for figure in ["laws.png", "cycle.png", "servo.png", "pick.png", "dobby.png", "front.png", "loom.png",
                   "response.png", "cam.png", "spectrum.png", "montecarlo.png"]:
        assert os.path.getsize(figure) > 10_000, figure
