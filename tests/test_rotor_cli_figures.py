"""Rotor features from the command line and figures that cannot mislead (issue 28): every figure a
rotor command writes has axes labelled with quantity and unit, the model's title and no overlapping
text (checked on the rendered text boxes of the figure as saved); the Campbell diagram lists
backward-whirl crossings apart from the critical speeds; ``static``, ``critical-map``,
``stability`` (threshold and API Level I), ``forced --plot DIR`` (Bode and polar), ``--html``,
``render`` of rotor files and the run-up's tracking filter."""
import json
import sys
import tomllib
from pathlib import Path

import matplotlib.figure
import numpy as np
import pytest

from fem.app.cli import main
from fem.output.figures.labels import figure_report, overlapping_texts

ROOT = Path(__file__).resolve().parent.parent
EX = ROOT / "examples"
FAN = EX / "rotor_overhung_fan.toml"
JEFFCOTT = EX / "rotor_jeffcott_seal.toml"
RPM = 30 / np.pi


@pytest.fixture
def figures(monkeypatch):
    """Every figure saved during the test: {file name: figure_report} (measured as saved)."""
    saved = {}
    original = matplotlib.figure.Figure.savefig

    def record(self, fname, *a, **k):
        out = original(self, fname, *a, **k)
        saved[Path(fname).name] = figure_report(self)
        return out

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", record)
    return saved


def _standards(saved, title):
    assert saved
    for name, rep in saved.items():
        assert rep["overlaps"] == [], f"{name}: overlapping texts {rep['overlaps']}"
        assert rep["without_unit"] == [], f"{name}: {rep['without_unit']}"
        assert any(" ".join(title.split()) in " ".join(t.split()) for t in rep["titles"]), \
            f"{name}: title {rep['titles']} lacks the model's"


def _title(path):
    return tomllib.loads(Path(path).read_text())["title"]


# ------------------------------------------------------------------ the checks themselves can fail
def test_overlap_and_unit_checks_catch_bad_figures():
    fig = matplotlib.figure.Figure()
    ax = fig.add_subplot()
    ax.plot([0, 1], [0, 1])
    ax.text(0.5, 0.5, "6574")
    ax.text(0.51, 0.5, "6430")
    ax.set_xlabel("speed")                    # no unit
    rep = figure_report(fig)
    assert ("6574", "6430") in rep["overlaps"]
    assert any("x label 'speed'" in b for b in rep["without_unit"]) and any("y label ''" in b for b in rep["without_unit"])


# ------------------------------------------------------------------ Campbell
def test_fan_backward_crossings_listed_apart(tmp_path, capsys, figures):
    """The isotropic overhung fan: three synchronous crossings below 6000 rev/min, the forward one the
    only critical speed; the backward ones (near 1460 and 5463 rev/min) apart in text, JSON and figure."""
    j, png = tmp_path / "c.json", tmp_path / "c.png"
    assert main(["campbell", str(FAN), "--json", str(j), "--plot", str(png), "--quiet"]) == 0
    out = capsys.readouterr().out
    d = json.loads(j.read_text())
    assert d["isotropic_supports"] is True
    assert [round(c["speed_rpm"]) for c in d["critical_speeds"]] == [3878]
    assert [round(c["speed_rpm"]) for c in d["backward_crossings"]] == [1460, 5463]
    assert {c["whirl"] for c in d["backward_crossings"]} == {"backward"}
    assert "critical speed (order 1): 1459" not in out and "critical speed (order 1): 5462" not in out
    assert "backward crossing (order 1): 1459.58" in out and "does not excite them" in out
    assert d["operating_range_rad_s"] == pytest.approx([2400 / RPM, 3000 / RPM])
    _standards(figures, _title(FAN))


def test_compressor_campbell_labels_do_not_overlap(tmp_path, figures):
    """The compressor's forward critical 6574 rev/min and backward crossing 6430 rev/min lie 1.7 Hz apart:
    their labels are placed apart (the check measures the rendered boxes)."""
    assert main(["campbell", str(EX / "rotor_compressor.toml"), "--plot", str(tmp_path / "c.png"), "--quiet"]) == 0
    _standards(figures, _title(EX / "rotor_compressor.toml"))


# ------------------------------------------------------------------ forced: Bode, polar, html
def test_forced_plot_file_or_directory(tmp_path, capsys, figures):
    assert main(["forced", str(JEFFCOTT), "--plot", str(tmp_path / "bode.png")]) == 0
    assert (tmp_path / "bode.png").is_file()
    d = tmp_path / "figs"
    assert main(["forced", str(FAN), "--plot", str(d)]) == 0
    names = sorted(p.name for p in d.iterdir())
    assert names[0] == "bode.png" and len([n for n in names if n.startswith("polar_")]) == 2
    assert "loads.png" in names and (tmp_path / "bode_loads.png").is_file()     # the named outputs' amplitudes
    _standards(figures, "")
    assert {k: any("Overhung fan" in t for t in r["titles"]) for k, r in figures.items()} == \
        {"bode.png": True, "bode_loads.png": False, "loads.png": True,     # bode_loads.png: the Jeffcott rotor's
         **{n: True for n in names if n.startswith("polar_")}}
    capsys.readouterr()
    assert main(["forced", str(JEFFCOTT), "--plot", str(tmp_path / "bode.txt")]) == 2
    assert "a .png file (one figure) or a directory" in capsys.readouterr().err


def test_html_outputs_and_missing_plotly(tmp_path, capsys, monkeypatch):
    pytest.importorskip("plotly")
    c, f = tmp_path / "c.html", tmp_path / "f.html"
    assert main(["campbell", str(JEFFCOTT), "--html", str(c), "--quiet"]) == 0
    assert main(["forced", str(JEFFCOTT), "--html", str(f)]) == 0
    for p in (c, f):
        text = p.read_text()
        assert "<html>" in text[:200] and "plotly" in text and "speed [rev\\u002fmin]" in text
    assert "log decrement [-]" in c.read_text() and "phase lag [deg]" in f.read_text()
    monkeypatch.setitem(sys.modules, "plotly", None)            # as if the extra were not installed
    monkeypatch.setitem(sys.modules, "plotly.graph_objects", None)
    capsys.readouterr()
    assert main(["campbell", str(JEFFCOTT), "--html", str(tmp_path / "x.html")]) == 2
    err = capsys.readouterr().err
    assert "pip install 'drivefem[html]'" in err and "Traceback" not in err
    assert not (tmp_path / "x.html").exists()


# ------------------------------------------------------------------ static, critical map, stability
def test_static_sag_cli_against_closed_form(tmp_path, figures):
    """Uniform shaft on two bearings under its own weight: the Timoshenko closed form (validation case
    rotor-static-sag) through the model file and the command."""
    L, d, kb, E, G, rho = 1.2, 0.06, 5e7, 211e9, 81.2e9, 7850.0
    text = f"""title = "Uniform shaft on two bearings"
[rotor]
[rotor.material]
E = {E}
G = {G}
rho = {rho}
[[rotor.segment]]
length = {L}
elements = 6
d = {d}
[[rotor.bearing]]
x = 0.0
kyy = {kb}
kzz = {kb}
name = "left"
[[rotor.bearing]]
x = {L}
kyy = {kb}
kzz = {kb}
name = "right"
"""
    p = tmp_path / "shaft.toml"
    p.write_text(text)
    j = tmp_path / "s.json"
    assert main(["static", str(p), "--json", str(j), "--plot", str(tmp_path / "s.png"), "--csv", str(tmp_path / "s.csv")]) == 0
    r = json.loads(j.read_text())
    A, I = np.pi * d**2 / 4, np.pi * d**4 / 64
    nu = E / (2 * G) - 1
    kappa = 6 * (1 + nu) / (7 + 6 * nu)
    w = rho * A * 9.81
    sag = 5 * w * L**4 / (384 * E * I) + w * L**2 / (8 * kappa * G * A) + w * L / (2 * kb)
    assert r["max_deflection_m"] == pytest.approx(sag, rel=1e-9) and r["max_deflection_x"] == pytest.approx(L / 2)
    assert np.array(r["bearing_force"])[:, 1] == pytest.approx([-w * L / 2] * 2, rel=1e-9)
    assert r["bearing_names"] == ["left", "right"] and r["equilibrium_error"] < 1e-12
    _standards(figures, "Uniform shaft on two bearings")


def test_critical_map_intersection_is_the_critical_speed(tmp_path, figures):
    """The fan's identical bearings (20 MN/m) cross the first forward curve of the map at the
    undamped forward critical speed, within 0.1 % of the damped one on the Campbell diagram (3878 rev/min)."""
    j = tmp_path / "m.json"
    assert main(["critical-map", str(FAN), "--json", str(j), "--plot", str(tmp_path / "m.png")]) == 0
    d = json.loads(j.read_text())
    first = min(d["intersections"], key=lambda c: c["speed_rad_s"])
    assert first["name"] == "bearing NDE, bearing DE" and first["stiffness"] == 2e7 and first["mode"] == 1
    assert first["speed_rad_s"] * RPM == pytest.approx(3878.2, rel=1e-3)
    assert d["backward_included"] is False and d["left_out"] == []
    _standards(figures, _title(FAN))


def test_stability_threshold_and_level1(tmp_path, capsys, figures):
    """Jeffcott rotor with a seal: threshold c w_n / beta, Level I Q0 = c w_n (validation case
    rotor-jeffcott-seal-cli has the closed forms); a five times stronger stage fails Level I."""
    j = tmp_path / "s.json"
    assert main(["stability", str(JEFFCOTT), "--json", str(j), "--plot", str(tmp_path / "s.png"), "--quiet"]) == 0
    d = json.loads(j.read_text())
    assert d["threshold"]["threshold_rad_s"] == pytest.approx(1866.78, rel=1e-5)
    lv = d["api_level1"]
    assert lv["q0_n_per_m"] == pytest.approx(56003.3, rel=1e-5) and lv["level_ii_required"] is False
    assert [c["passed"] for c in lv["criteria"]] == [True, True] and lv["placement"] == "mid-span"
    assert "passes Level I" in capsys.readouterr().out
    _standards(figures, _title(JEFFCOTT))
    from fem.modelfile.build.rotor import level1_spec, operating_range
    from fem.rotor.api_level1 import api_level1
    from fem.study import Study

    study = Study.load(JEFFCOTT)
    spec = level1_spec(study.doc, operating_range(study.doc))
    spec["stages"][0].power *= 5
    lv = api_level1(study.rotor.rotor, n_modes=2, **spec)
    assert not lv.passed and lv.ratio == pytest.approx(56003.3 / (5 * 23873.2), rel=1e-5)
    assert [c["passed"] for c in lv.criteria] == [False, False]


@pytest.mark.parametrize("change, pattern", [
    (("exclude = [\"seal\"]", "exclude = [\"labyrinth\"]"), r"exclude = 'labyrinth'.*names of \[\[rotor.bearing\]\]s"),
    (("speed_rpm = 12000                  # maximum", "machine = \"radial\"  # maximum"), r"machine"),
    (("[stability]\nspeeds_rpm = { start = 1000, stop = 24000, points = 24 }", "[stability]"), None),
])
def test_stability_bad_input(tmp_path, capsys, change, pattern):
    doc = JEFFCOTT.read_text().replace(*change)
    p = tmp_path / "bad.toml"
    p.write_text(doc)
    rc = main(["stability", str(p), "--quiet"])
    err = capsys.readouterr().err
    if pattern is None:                        # no [stability] speeds: the [campbell] speeds are scanned
        assert rc == 0
        return
    import re

    assert rc == 2 and "Traceback" not in err and re.search(pattern, err), err


def test_render_needs_a_rotor_or_fe_file(tmp_path, capsys):
    assert main(["render", str(EX / "two_mass_chain.toml"), "--out", str(tmp_path / "r")]) == 2
    assert "an FE or rotor model file" in capsys.readouterr().err


# ------------------------------------------------------------------ progress
def test_progress_bar_only_on_a_terminal_and_not_quiet(monkeypatch):
    import io

    from fem.app.progress import count_bar

    class Tty(io.StringIO):
        def isatty(self):
            return True

    for quiet, tty, shown in ((False, True, True), (True, True, False), (False, False, False)):
        err = Tty() if tty else io.StringIO()
        monkeypatch.setattr(sys, "stderr", err)
        with count_bar("campbell", "solves", quiet=quiet, delay=0.0) as update:
            for k in range(1, 4):
                update(k, 3)
        assert ("campbell" in err.getvalue()) is shown, (quiet, tty)


# ------------------------------------------------------------------ run-up tracking filter
def test_run_up_tracking_filter_converges_to_the_steady_response():
    """A slow linear run-up (no rub) of the fan: the 1x amplitude and phase lag of the tracking filter
    equal the steady unbalance response away from the critical speed (ramp effects < 1 %)."""
    from fem.rotor import Probe, RunUp, Unbalance, rpm, run_up, unbalance_response
    from fem.rotor.runup_tracking import synchronous_response
    from fem.study import Study

    rs = Study.load(FAN).rotor
    unb = [Unbalance(0.8, 3e-4)]
    res = run_up(rs, RunUp(rpm(1500), rpm(2000), 1.5, modes=6), unb, probes=[0.8])
    sync = synchronous_response(res, revolutions=4, points=20)
    steady = unbalance_response(rs, unb, sync.speed_rad_s, probes=[Probe(0.8, "major")], find_peaks=False)
    p = steady.probes[0]
    np.testing.assert_allclose(sync.amplitude[:, 0], p.amplitude, rtol=1e-2)
    lag = np.angle(np.exp(1j * np.radians(sync.phase_lag_deg[:, 0] - p.phase_lag_deg)))
    assert np.degrees(np.abs(lag)).max() < 1.0


@pytest.fixture(scope="module")
def can_render():
    import os

    from fem.render import available

    ok, msg = available()
    if not ok:
        if os.environ.get("DRIVEFEM_REQUIRE_RENDER") == "1":
            pytest.fail(f"rendering required but unavailable: {msg}")
        pytest.skip(msg)
    return True


def test_render_rotor_file_png_and_gif(can_render, tmp_path):
    """drivefem render on a rotor file: the whirl of mode 1 (forward at 10000 rev/min) as a PNG and a
    GIF, off screen; the frames differ over a period; data files first."""
    import imageio.v2 as imageio

    from fem.render.pixels import body_mask, difference_fraction

    out = tmp_path / "r"
    assert main(["render", str(JEFFCOTT), "--out", str(out), "--mode", "1", "--gif", "--quiet"]) == 0
    names = sorted(p.name for p in out.iterdir())
    assert names == ["mode01_forward.gif", "mode01_forward.png", "modes.csv", "modes.json"]
    img = imageio.imread(out / "mode01_forward.png")
    assert 0.01 < body_mask(img[..., :3]).mean() < 0.6
    frames = imageio.mimread(out / "mode01_forward.gif")
    assert len(frames) == 24 and difference_fraction(frames[0][..., :3], frames[12][..., :3]) > 0.002
    assert json.loads((out / "modes.json").read_text())["schema"] == "drivefem.modal"


def test_static_of_a_full_model_and_map_bearing_names(tmp_path, capsys):
    """A 'full' model (axial, torsion free: unloaded, they stay at rest) has the lateral model's sag;
    [critical_map] bearings must name bearings of the file."""
    j = tmp_path / "s.json"
    assert main(["static", str(EX / "rotor_friswell.toml"), "--json", str(j)]) == 0
    assert json.loads(j.read_text())["max_deflection_m"] == pytest.approx(1443.85e-6, abs=0.01e-6)
    doc = FAN.read_text() + '\n[critical_map]\nbearings = ["bearing NDE", "bearing X"]\n'
    p = tmp_path / "fan.toml"
    p.write_text(doc)
    capsys.readouterr()
    assert main(["critical-map", str(p)]) == 2
    assert "bearings = 'bearing X'" in capsys.readouterr().err
