"""Shards for a cluster (issue 28 item 7): `shard=(i, n)` gives exactly the rows of the CLI's
`--shard i/n`, the shards concatenated are the unsharded call, and a Monte-Carlo report made from
the shards' per-draw tables (or the CLI's parts) equals the unsharded report — at n = 2, 3, 7 and
more shards than rows. Ends with the Dask recipe of docs/python.md on a LocalCluster."""

import csv
import io
import json

import numpy as np
import pytest

import loomkin
from conftest import REPO, records, same

NS = (2, 3, 7)


def _lines(text):
    """JSON Lines (a sharded `--json`) as a list of records."""
    return [json.loads(line) for line in text.splitlines() if line.strip()]


def _csv(text, names=None):
    """A CSV table as a dict of float columns: header in the first line, or `names` for a later
    shard's standard output (which has none)."""
    rows = list(csv.reader(io.StringIO(text)))
    if names is None:
        names, rows = rows[0], rows[1:]
    return {k: np.array([float(r[i]) for r in rows]) for i, k in enumerate(names)}


def _same_table(a, b):
    assert list(a) == list(b)
    for k in a:
        if isinstance(a[k], np.ndarray):
            np.testing.assert_array_equal(a[k], b[k], err_msg=k)
        else:
            assert list(a[k]) == list(b[k]), k


def _no_none(rows):
    return [{k: v for k, v in r.items() if v is not None} for r in rows]


@pytest.mark.parametrize("n", NS + (150,))
def test_law_sample_shards(cli, n):
    whole = loomkin.laws.sample("cycloidal", 101)
    parts = [loomkin.laws.sample("cycloidal", 101, shard=(i, n)) for i in range(1, n + 1)]
    assert all(isinstance(p, loomkin.Table) for p in parts)
    _same_table(loomkin.concat(parts), whole)
    for i in {1, 2, n}:
        ref = _lines(cli("law", "sample", "cycloidal", "--points", "101", "--shard", f"{i}/{n}", "--json", text=True))
        same(records(parts[i - 1]), ref)
    # The law object takes the same shard ("I/N" text too).
    _same_table(loomkin.Law("cycloidal").sample(101, f"2/{n}"), parts[1])


@pytest.mark.parametrize("n", NS + (12,))
def test_pick_sweep_shards(cli, n):
    args = ("speed", 160, 240, 9)
    whole = loomkin.picking.sweep(*args)
    parts = [loomkin.picking.sweep(*args, shard=(i, n)) for i in range(1, n + 1)]
    _same_table(loomkin.concat([p["rows"] for p in parts]), whole["rows"])
    for i in {1, 2, n}:
        ref = _lines(cli("pick", "sweep", "speed", "--from", "160", "--to", "240", "--points", "9",
                         "--shard", f"{i}/{n}", "--json", text=True))
        same(_no_none(records(parts[i - 1]["rows"])), ref)


@pytest.mark.parametrize("n", NS + (20,))
def test_shed_table_shards(cli, n):
    whole = loomkin.shed.table(design="table1", motion_deg="240,300")
    parts = [loomkin.shed.table(design="table1", motion_deg="240,300", shard=(i, n)) for i in range(1, n + 1)]
    _same_table(loomkin.concat(parts), whole)
    for i in {1, n}:
        ref = _lines(cli("shed", "table", "--design", "table1", "--motion-deg", "240,300", "--shard", f"{i}/{n}",
                         "--json", text=True))
        same(_no_none(records(parts[i - 1])), ref)


@pytest.mark.parametrize("n", NS + (100,))
def test_dyn_sweep_shards(cli, n):
    file = REPO / "examples" / "heald-frame-cycle.toml"
    speeds = np.arange(200.0, 1000.0 + 1e-9, 10.0)
    whole = loomkin.dynamics.sweep(file, speeds, 54)
    parts = [loomkin.dynamics.sweep(file, speeds, 54, shard=(i, n)) for i in range(1, n + 1)]
    _same_table(loomkin.concat([p["points"] for p in parts]), whole["points"])
    ref = _csv(cli("dyn", "sweep", "examples/heald-frame-cycle.toml", "--natural-hz", "54", "--speed-rpm",
                   "200:1000:10", "--shard", f"1/{n}", "--csv", text=True))
    _same_table(parts[0]["points"], ref)


@pytest.mark.parametrize("n", (2, 3, 5))
def test_dobby_sweep_shards(cli, n):
    whole = loomkin.dobby.sweep([40, 45, 50], step_deg=2)
    parts = [loomkin.dobby.sweep([40, 45, 50], step_deg=2, shard=(i, n)) for i in range(1, n + 1)]
    _same_table(loomkin.concat([p["rows"] for p in parts]), whole["rows"])
    ref = _lines(cli("dobby", "sweep", "--from", "40", "--to", "50", "--by", "5", "--step-deg", "2",
                     "--shard", f"{n}/{n}", "--json", text=True))
    same(records(parts[-1]["rows"]), ref)


def _study(tmp_path, name, draws, **extra):
    tomllib = pytest.importorskip("tomllib")

    from loomkin._inputs import study_text

    d = tomllib.loads((REPO / "examples" / name).read_text())
    d["draws"] = draws
    d.update(extra)
    path = tmp_path / name
    path.write_text(study_text(d))
    return d, path


@pytest.mark.parametrize("n", NS + (250,))
def test_pick_montecarlo_report_from_shards(cli, tmp_path, n):
    d, path = _study(tmp_path, "pick-montecarlo.toml", 200)
    whole = loomkin.picking.montecarlo(d)
    per_draw = whole.pop("per_draw")
    tables = [loomkin.picking.montecarlo(d, shard=(i, n)) for i in range(1, n + 1)]
    assert all(isinstance(t, loomkin.Table) for t in tables)
    _same_table(loomkin.concat(tables), per_draw)
    # The report from the shards' tables is the unsharded report, every number bit for bit; as
    # DataFrames too (what a Dask or pandas user holds).
    same(loomkin.picking.montecarlo(d, from_draws=tables), whole)
    same(loomkin.picking.montecarlo(d, from_draws=[t.frame() for t in tables]), whole)
    # A shard's table is the CLI's `--shard i/n --csv`, value for value.
    i = min(3, n)
    text = cli("pick", "montecarlo", path, "--shard", f"{i}/{n}", "--csv", text=True)
    _same_table(tables[i - 1], _csv(text, None if i == 1 else list(per_draw)))
    # The CLI's parts (`--parts DIR`, a header in each) are read by the same call.
    if n <= 3:
        parts = tmp_path / f"parts-{n}"
        for i in range(1, n + 1):
            cli("pick", "montecarlo", path, "--shard", f"{i}/{n}", "--parts", parts, "--csv", text=True)
        same(loomkin.picking.montecarlo(d, from_draws=str(parts)), whole)
        same(loomkin.picking.montecarlo(d, from_draws=sorted(parts.glob("part-*.csv"))), whole)


@pytest.mark.parametrize("n", (2, 7, 40))
def test_dobby_tolerance_report_from_shards(cli, tmp_path, n):
    d, path = _study(tmp_path, "dobby-tolerance.toml", 30, step_deg=4)
    whole = loomkin.dobby.tolerance(d)
    per_draw = whole.pop("per_draw")
    tables = [loomkin.dobby.tolerance(d, shard=(i, n)) for i in range(1, n + 1)]
    _same_table(loomkin.concat(tables), per_draw)
    same(loomkin.dobby.tolerance(d, from_draws=tables), whole)
    _same_table(tables[1], _csv(cli("dobby", "tolerance", path, "--shard", f"2/{n}", "--csv", text=True), list(per_draw)))


def test_shard_and_reduce_errors(tmp_path):
    d, _ = _study(tmp_path, "pick-montecarlo.toml", 20)
    for bad in [(0, 3), (4, 3), (1, 0), "x", (-1, 2), "2/3/4"]:
        with pytest.raises(loomkin.LoomkinError) as e:
            loomkin.laws.sample("cycloidal", 11, shard=bad)
        assert e.value.field == "shard" and "1 ≤ I ≤ N" in e.value.allowed, bad
    tables = [loomkin.picking.montecarlo(d, shard=(i, 3)) for i in (1, 2, 3)]
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.picking.montecarlo(d, from_draws=tables[:2])
    assert e.value.field == "from_draws" and "draws where the study has 20" in str(e.value)
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.picking.montecarlo(d, from_draws=[tables[1], tables[0], tables[2]])
    assert e.value.field == "from_draws" and "where draw 0 belongs" in str(e.value)
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.picking.montecarlo(d, shard=(1, 2), from_draws=tables)
    assert e.value.field == "from_draws"
    other = {k: v for k, v in list(tables[0].items())[1:]}
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.picking.montecarlo(d, from_draws=[other])
    assert "are not those of pick montecarlo --csv" in str(e.value)
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.concat([tables[0], other])
    assert e.value.field == "tables"


@pytest.mark.parametrize("n", (1, 2, 3, 7, 250))
def test_montecarlo_report_from_summaries(cli, tmp_path, n):
    """Summaries instead of draws: the report without percentiles and histograms, counts and
    extremes bit for bit, mean and sd to 1e-12; the CLI's --summary files are read too."""
    d, path = _study(tmp_path, "pick-montecarlo.toml", 200)
    whole = loomkin.picking.montecarlo(d)
    whole.pop("per_draw")
    parts = [loomkin.picking.montecarlo(d, shard=(i, n), summary=True) for i in range(1, n + 1)]
    got = loomkin.picking.montecarlo(d, from_summaries=parts[::-1])
    same(got, loomkin.picking.montecarlo(d, from_summaries=[str(_write(tmp_path, cli, path, n))]))

    def close(g, w, at="$"):
        if isinstance(w, dict):
            keys = [k for k in w if k not in ("percentiles", "histogram")]
            assert sorted(g) == sorted(keys), at
            for k in keys:
                if k in ("mean", "sd"):
                    assert g[k] == pytest.approx(w[k], rel=1e-12, abs=0), f"{at}.{k}"
                else:
                    close(g[k], w[k], f"{at}.{k}")
        elif isinstance(w, list):
            assert len(g) == len(w), at
            for i, (a, b) in enumerate(zip(g, w)):
                close(a, b, f"{at}[{i}]")
        else:
            assert g == w, at

    close(got, whole)
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.picking.montecarlo(d, from_summaries=parts[:-1])  # the last shard is never empty
    assert e.value.field == "from_summaries"


def _write(tmp_path, cli, path, n):
    """The CLI's --summary of every shard, concatenated into one file."""
    f = tmp_path / f"summaries-{n}.jsonl"
    f.write_text("".join(cli("pick", "montecarlo", path, "--shard", f"{i}/{n}", "--summary", text=True)
                         for i in range(1, n + 1)))
    return f


def test_dask_local_cluster_matches_the_unsharded_run(tmp_path):
    """The recipe of docs/python.md: shards mapped over a Dask cluster, the reduce on the client."""
    distributed = pytest.importorskip("dask.distributed", reason="dask[distributed] is not installed: "
                                      "pip install 'loomkin[test]' (CI installs it)")
    d, _ = _study(tmp_path, "pick-montecarlo.toml", 300)
    n = 7
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        futures = client.map(lambda i: loomkin.picking.montecarlo(d, shard=(i, n)), range(1, n + 1))
        tables = client.gather(futures)
        sweeps = client.gather(client.map(lambda i: loomkin.picking.sweep("speed", 160, 240, 41, shard=(i, n))["rows"],
                                          range(1, n + 1)))
    whole = loomkin.picking.montecarlo(d)
    per_draw = whole.pop("per_draw")
    _same_table(loomkin.concat(tables), per_draw)
    same(loomkin.picking.montecarlo(d, from_draws=tables), whole)
    _same_table(loomkin.concat(sweeps), loomkin.picking.sweep("speed", 160, 240, 41)["rows"])
