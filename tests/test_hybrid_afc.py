"""Amplitude-frequency curves and sweeps of hybrid FE models from the command line (issue 12, item 2):
``drivefem forced`` with a ``[steady]`` table on the two hybrid AFC examples (shortened ranges),
``drivefem sweep`` on the hybrid sweep example (serial, --workers 0) and ``drivefem simulate`` of the
examples' time-domain variant ([simulation], shortened).  The numbers asserted are long time
simulations of the same models (validation case hybrid_afc_*), within the HB curves' own accuracy.

BLAS is limited to one thread around each command: the curves solve many small dense systems, where a
multi-threaded BLAS on a loaded 2-core machine costs 5-10x in wall time (reported to the lead)."""
import json
import tomllib
from pathlib import Path

import pytest

from discrete.linalg import single_threaded_blas
from fem.app.cli import main

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
IMPACT = EXAMPLES / "hybrid_afc_vibro_impact.toml"
ROD = EXAMPLES / "hybrid_afc_friction_rod.toml"
SWEEP = EXAMPLES / "hybrid_sweep_vibro_impact.toml"


def variant(path: Path, tmp_path: Path, replace: dict[str, str]) -> Path:
    """A copy of an example with some lines replaced (exact text, each must occur once)."""
    text = path.read_text()
    for old, new in replace.items():
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    out = tmp_path / path.name
    out.write_text(text)
    return out


def run(argv) -> int:
    with single_threaded_blas():
        return main([str(a) for a in argv])


def forced_json(model: Path, tmp_path: Path) -> dict:
    js, csv, png = tmp_path / "afc.json", tmp_path / "afc.csv", tmp_path / "afc.png"
    assert run(["forced", model, "--json", js, "--csv", csv, "--plot", png]) == 0
    data = json.loads(js.read_text())
    assert data["schema"] == "drivefem.forced" and data["kind"] == "hybrid"
    assert data["steady"] is True and data["completed"] is True and data["stop_cause"] == "end"
    assert len(data["omega_rad_s"]) == data["n_points"] == len(data["stable"]) > 3
    # the output contract's one shape: outputs x frequencies; the curve is amplitude[0]
    assert data["outputs"] == [data["response_label"]] and len(data["amplitude"][0]) == data["n_points"]
    assert csv.read_text().splitlines()[0].startswith("omega_rad_s") and png.stat().st_size > 0
    return data


def test_forced_vibro_impact_cantilever(tmp_path):
    """HB-25 over 300 .. 340 rad/s (contact starts at 314 rad/s); at 340 rad/s the peak stop force of a
    90-period simulation of the same model is 31.898 N (the curve: within 1e-3)."""
    model = variant(IMPACT, tmp_path, {"omega = [250.0, 450.0]": "omega = [300.0, 340.0]"})
    data = forced_json(model, tmp_path)
    assert data["omega_rad_s"][0] == 300.0 and data["omega_rad_s"][-1] == pytest.approx(340.0, rel=1e-12)
    curve = data["amplitude"][0]
    assert curve[0] == 0.0                                         # no contact yet
    assert curve[-1] == pytest.approx(31.898, rel=1e-3)
    assert all(data["stable"]) and not data["folds"]
    assert data["response_label"] == "max |F| stop"


def test_forced_friction_rod(tmp_path):
    """HB-15 (tanh friction) over z = 0.95 .. 1.05: the peak tip amplitude equals the simulated exact
    stick-slip/slip amplitude at that frequency, 15.615 um, within 1e-3 (HB's truncation at the peak)."""
    model = variant(ROD, tmp_path, {"z = [0.85, 1.15]": "z = [0.95, 1.05]"})
    data = forced_json(model, tmp_path)
    assert data["z"][0] == 0.95 and data["z"][-1] == pytest.approx(1.05, rel=1e-12)
    assert data["peak"]["response"] == pytest.approx(15.615, rel=1e-3)
    assert abs(data["peak"]["omega_rad_s"] / data["omega_ref_rad_s"] - 1) < 2e-3
    assert all(data["stable"]) and not data["folds"]


def test_sweep_vibro_impact_serial(tmp_path):
    """The sweep example (force amplitude x frequency, "steady" points: integration from rest +
    shooting + Floquet) serially; the point (10 N, 370 rad/s) lies on the AFC (71.398 N, HB-25 of the
    same model, validation case hybrid_afc_vibro_impact) within 1e-3; the points are stable."""
    js = tmp_path / "map.json"
    assert run(["sweep", SWEEP, "--workers", "0", "--json", js, "--out", tmp_path / "points"]) == 0
    data = json.loads(js.read_text())
    assert data["schema"] == "drivefem.sweep" and data["analysis"] == "steady"
    assert data["n_points"] == data["n_ok"] == 6 and data["n_failed"] == 0
    pts = {(p["values"]["force.0.amplitude"], p["values"]["force.0.omega"]): p["result"] for p in data["points"]}
    res = pts[(10.0, 370.0)]
    assert res["converged"] and res["stable"] and res["settled"]
    assert res["response"] == pytest.approx(71.398, rel=1e-3)
    assert res["response_observed"] == pytest.approx(res["response"], rel=1e-5)
    assert pts[(5.0, 370.0)]["response"] == 0.0            # 5 N: the beam never reaches the stop there


@pytest.mark.parametrize("path", [IMPACT, ROD], ids=lambda p: p.name)
def test_simulate_time_domain_variant(path, tmp_path):
    """``drivefem simulate`` runs the examples' [simulation] (shortened to a sixth) with the event-driven
    solver: JSON contract, energy balance closed, one contact or two slip reversals per period."""
    t_end = tomllib.loads(path.read_text())["simulation"]["t_end"]
    model = variant(path, tmp_path, {f"t_end = {t_end}": f"t_end = {t_end / 6!r}"})
    js = tmp_path / "sim.json"
    assert run(["simulate", model, "--json", js]) == 0
    data = json.loads(js.read_text())
    assert data["schema"] == "drivefem.simulate" and data["kind"] == "hybrid" and not data["stopped_early"]
    assert data["t_reached"] == pytest.approx(t_end / 6) and data["energy_error"] < 1e-8
    counts = data["event_counts"]
    if path == IMPACT:
        assert counts.get("contact_close", 0) >= 5          # 370 rad/s: one contact per period (7 periods)
    else:
        assert counts.get("reversal", 0) >= 40              # resonance: two reversals per period (25 periods)
