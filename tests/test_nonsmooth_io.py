"""Model files, JSON contract, CSV and plots of the nonsmooth simulations; validation cases pass."""
import csv
import json
import pathlib
import tomllib

import numpy as np
import pytest

from fem.output import columns
from fem.output.figures import plot_time_history
from fem.study import simulate

ROOT = pathlib.Path(__file__).resolve().parents[1]
EXAMPLES = sorted((ROOT / "examples").glob("discrete_*.toml"))


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_examples_run_and_json_contract(path):
    with path.open("rb") as fh:
        doc = tomllib.load(fh)
    res = simulate(doc)
    d = json.loads(json.dumps(res.to_dict()))
    for key in ("t_end", "events", "period", "energy_error"):
        assert key in d
    assert d["t_end"] == doc["simulation"]["t_end"]
    assert not d["stopped_early"]
    bodies = {b["name"] for b in doc["body"]}
    for ev in d["events"]:
        assert set(ev) == {"t", "kind", "element", "state"}
        assert ev["kind"] in {"stick", "slip", "reversal", "impact", "contact_open", "contact_close"}
        assert bodies <= set(ev["state"]) and all(set(s) == {"x", "v"} for s in ev["state"].values())
    assert d["energy_error"] is None or d["energy_error"] < 1e-8


def test_seed000_example_period():
    from validation.analytic import seed000
    with (ROOT / "examples" / "discrete_seed000_stick_slip.toml").open("rb") as fh:
        d = simulate(tomllib.load(fh)).to_dict()
    ref = seed000.dimensional(6.0, 1.5, 2.0, 50.0, 3.0)
    assert d["period"] == pytest.approx(ref["period"], rel=1e-10)
    assert d["period_info"]["per_period"] == {"slip": 1, "reversal": 2, "stick": 1}


def test_csv_and_plots(tmp_path):
    with (ROOT / "examples" / "discrete_seed000_stick_slip.toml").open("rb") as fh:
        res = simulate(tomllib.load(fh))
    p = tmp_path / "out" / "h.csv"
    columns.write(p, columns.time_history(res))
    rows = list(csv.reader(p.open()))
    assert rows[0][:5] == ["t", "disk.x", "disk.v", "top.x", "top.v"] and rows[0][-2:] == ["energy", "work"]
    data = np.array(rows[1:], dtype=float)
    assert data.shape == (res.t.size, 7)
    assert np.array_equal(data[:, 0], res.t) and np.array_equal(data[:, 2], res.v[0])
    paths = plot_time_history(res, tmp_path / "png")
    names = {q.name for q in paths}
    assert {"time.png", "phase_disk.png", "energy.png"} <= names
    for q in paths:
        assert q.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and q.stat().st_size > 2000


def test_fast_discrete_validation_cases_pass():
    from validation.registry import run_case, select

    cases = [c for c in select(["discrete"]) if not c.slow]
    assert len(cases) >= 7
    for c in cases:
        out = run_case(c)
        assert out.error is None, (c.name, out.error)
        bad = [ch for ch in out.checks if not ch.passed]
        assert not bad, (c.name, bad[:3])
