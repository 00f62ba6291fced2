"""Figure standards (issue 28) on the figures of the FE, lumped and hybrid commands, measured on the
figures as saved (fem.output.figures.labels.figure_report): every axis with numbers has a label
``quantity [unit]``, the model's title is on the figure, no text overlaps another, colour that
encodes a value has a colour bar, and the legends carry the names of the model file.  The rotor
figures are checked the same way in tests/test_rotor_cli_figures.py."""
import tomllib
from pathlib import Path

import matplotlib.figure
import pytest

from fem.app.cli import main
from fem.output.figures.labels import figure_report

ROOT = Path(__file__).resolve().parent.parent
EX = ROOT / "examples"


@pytest.fixture
def figures(monkeypatch):
    """Every figure saved during the test: {file name: (figure_report, legend texts)}."""
    saved = {}
    original = matplotlib.figure.Figure.savefig

    def record(self, fname, *a, **k):
        out = original(self, fname, *a, **k)
        legends = [t.get_text() for ax in self.axes if ax.get_legend() for t in ax.get_legend().get_texts()]
        legends += [t.get_text() for leg in self.legends for t in leg.get_texts()]
        saved[Path(fname).name] = (figure_report(self), legends)
        return out

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", record)
    return saved


def _title(example):
    return " ".join(tomllib.loads((EX / example).read_text())["title"].split())


def _standards(saved, title, expected):
    assert set(saved) == set(expected), sorted(saved)
    for name, (rep, _) in saved.items():
        assert rep["overlaps"] == [], f"{name}: overlapping texts {rep['overlaps']}"
        assert rep["without_unit"] == [], f"{name}: {rep['without_unit']}"
        assert rep["without_colour_bar"] == [], f"{name}: {rep['without_colour_bar']}"
        assert any(title in " ".join(t.split()) for t in rep["titles"]), f"{name}: {rep['titles']}"


def test_stick_slip_time_phase_and_energy(tmp_path, figures):
    """The drill-string stick-slip seed: named outputs (relative twist of the spring, slip velocity,
    loads), the speeds of the disk and the driven top, the events by kind, a phase portrait of the
    disk and the energy balance.  The spring's force equals the top's reaction: one curve, both names."""
    ex = "discrete_seed000_stick_slip.toml"
    assert main(["simulate", str(EX / ex), "--plot", str(tmp_path / "f"), "--quiet"]) == 0
    _standards(figures, _title(ex), {"time.png", "phase_disk.png", "energy.png"})
    legends = figures["time.png"][1]
    assert "spring[1] top-disk.deflection" in legends and "bit.slip_velocity" in legends
    assert "spring[1] top-disk.force = top.reaction" in legends and {"disk", "top (driven)"} <= set(legends)
    rep = figures["time.png"][0]
    assert any("speed" in t or "velocity" in t for t in rep["titles"] + legends)


def test_hybrid_field_coupling_loads_energy(tmp_path, figures):
    """The elastic bar hitting a wall: u(x, t) with a colour bar in metres, the DOF at the wall, the
    named outputs (wall and section forces) and the energy balance."""
    ex = "hybrid_bar_wall.toml"
    assert main(["simulate", str(EX / ex), "--plot", str(tmp_path / "f"), "--quiet"]) == 0
    _standards(figures, _title(ex), {"field.png", "coupling.png", "loads.png", "energy.png"})
    assert {"wall.force", "wall.deflection"} <= set(figures["loads.png"][1])


def test_fe_frf_and_mode_shapes(tmp_path, figures):
    """FE cantilever: the harmonic response (amplitude with quantity and unit, phase lag) and the
    stepped rotor's mode shapes, one panel per mode above the shaft with its supports and disc."""
    ex = "cantilever.toml"
    assert main(["forced", str(EX / "forced_torsion.toml"), "--plot", str(tmp_path / "frf.png"), "--quiet"]) == 0
    _standards(figures, _title("forced_torsion.toml"), {"frf.png"})
    figures.clear()
    assert main(["modal", str(EX / ex), "--plot", str(tmp_path / "modes.png"), "--quiet"]) == 0
    _standards(figures, _title(ex), {"modes.png"})


@pytest.mark.slow
def test_amplitude_frequency_curve_legend_in_words(tmp_path, figures):
    """The Duffing oscillator's [steady] curve: branches, folds and backbone named in words, the
    legend off the curves."""
    ex = "steady_duffing.toml"
    assert main(["forced", str(EX / ex), "--plot", str(tmp_path / "afc.png"), "--quiet"]) == 0
    _standards(figures, _title(ex), {"afc.png"})
    legends = figures["afc.png"][1]
    assert any("stable branch" in t for t in legends) and "fold (turning point)" in legends
    assert not any("(stable)" in t or "AFT" in t for t in legends)


@pytest.mark.slow
@pytest.mark.parametrize("argv, names", [
    (["parametric", "parametric_drive.toml", "--plot", "chart.png"], {"chart.png"}),
    (["forced", "motor_drive_forced.toml", "--plot", "f"], {"frf.png", "loads.png"}),
    (["forced", "drive_forced.toml", "--plot", "frf.png"], {"frf.png"}),
    (["simulate", "geared_mesh.toml", "--plot", "f"], None),
    (["simulate", "discrete_bouncing_ball.toml", "--plot", "f"], None),
    (["simulate", "hybrid_drill_string.toml", "--plot", "f"], None),
    (["simulate", "rotor_rub_runup.toml", "--plot", "f"], None),
])
def test_more_figure_types_meet_the_standards(tmp_path, figures, argv, names):
    """Further figure types of the demo: the parametric chart, drive FRFs with named outputs, geared and
    impact time histories, a hybrid drill string, a rotor run-up through a rub."""
    command, example, option, target = argv
    assert main([command, str(EX / example), option, str(tmp_path / target), "--quiet"]) == 0
    _standards(figures, _title(example), names or set(figures))


# ---- every figure type of the demo (``drivefem demo`` / ``make demo``) -------------------------------
# The runs come from the demo's own run list (fem.app.demo._run_list) and the Python examples it runs
# (examples/*.py), so a new command, example or figure in the demo is checked here without a new test.
# Each figure the run saves is checked against the standards, and its gallery type
# (fem.app.gallery.figure_type) must have a caption.  The cheap runs are in the default tier, the rest
# in the slow tier.

from fem.app.demo import _run_list  # noqa: E402
from fem.app.gallery import caption, figure_type  # noqa: E402

DEMO_OUT = Path("/drivefem-demo-out")        # placeholder the run list is made with; replaced by tmp_path
#: demo runs cheap enough for the default tier (seconds each); every other run is in the slow tier
DEFAULT_TIER_RUNS = {"forced beam_base_excitation.toml", "simulate cam_clearance.toml", "modal cantilever.toml",
                     "forced sdof_base_motion.toml", "modal rotor_friswell.toml", "static rotor_overhung_fan.toml"}
DEFAULT_TIER_PYTHON = {"cam_report", "absorber_design", "drive_spectrum"}


def _demo_runs():
    runs = []
    for argv, kind in _run_list(DEMO_OUT):
        if argv[0] == "sweep":           # the demo shows these, it does not run them (minutes of work)
            continue
        ident = f"{argv[0]} {Path(argv[1]).name}"
        if argv[0] == "render":
            continue                     # pictures (pyvista), checked in test_demo_render_pictures
        marks = [] if ident in DEFAULT_TIER_RUNS else [pytest.mark.slow]
        runs.append(pytest.param(argv, kind, id=ident.replace(" ", ":"), marks=marks))
    return runs


@pytest.fixture
def drawn(monkeypatch):
    """Every figure saved during the test: [(path, figure_report, legend texts)]."""
    saved = []
    original = matplotlib.figure.Figure.savefig

    def record(self, fname, *a, **k):
        out = original(self, fname, *a, **k)
        legends = [t.get_text() for ax in self.axes if ax.get_legend() for t in ax.get_legend().get_texts()]
        legends += [t.get_text() for leg in self.legends for t in leg.get_texts()]
        saved.append((Path(fname), figure_report(self), legends))
        return out

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", record)
    return saved


def _uncaptioned(out, command, kind) -> list[str]:
    """Gallery types without a caption of the pictures written under ``out`` (PNG and GIF, the 3D
    pictures included: the gallery shows them all)."""
    types = {figure_type(p, out, command, kind) for p in out.rglob("*") if p.suffix in (".png", ".gif")}
    return sorted(t for t in types if caption(t) is None)


def _meets_standards(path, rep, title=None):
    assert rep["overlaps"] == [], f"{path.name}: overlapping texts {rep['overlaps']}"
    assert rep["without_unit"] == [], f"{path.name}: {rep['without_unit']}"
    assert rep["without_colour_bar"] == [], f"{path.name}: {rep['without_colour_bar']}"
    assert rep["titles"], f"{path.name}: no title"
    if title is not None:
        assert any(title in " ".join(t.split()) for t in rep["titles"]), f"{path.name}: {rep['titles']}"


@pytest.mark.parametrize("argv, kind", _demo_runs())
def test_demo_figures_meet_the_standards(tmp_path, drawn, argv, kind):
    """One command of the demo's run list, its output paths moved to ``tmp_path``: every figure it draws
    meets the standards, carries the model's title, and has a gallery type with a caption."""
    argv = [str(tmp_path / Path(a).relative_to(DEMO_OUT)) if a.startswith(str(DEMO_OUT)) else a for a in argv]
    assert main(argv + ["--quiet"]) == 0
    title = _title(Path(argv[1]).name)
    for path, rep, _ in drawn:
        _meets_standards(path, rep, title)
    assert _uncaptioned(tmp_path, argv[0], kind) == []


def _python_examples():
    return [pytest.param(p.stem, id=p.stem, marks=[] if p.stem in DEFAULT_TIER_PYTHON else [pytest.mark.slow])
            for p in sorted(EX.glob("*.py"))]


@pytest.mark.parametrize("name", _python_examples())
def test_demo_python_example_figures_meet_the_standards(tmp_path, drawn, name):
    """A Python example the demo runs (examples/<name>.py, its ``main`` into the demo's layout): every
    figure meets the standards and has a gallery type with a caption."""
    from fem.app.demo import _python_examples as run_examples

    runs = [(n, rc) for n, rc, _ in run_examples(tmp_path / "python", [EX / f"{name}.py"])]
    assert runs == [(f"{name}.py", 0)]
    for path, rep, _ in drawn:
        _meets_standards(path, rep)
    assert _uncaptioned(tmp_path, "python", "") == []


def test_demo_validation_report_figures(tmp_path, drawn):
    """The validation report's figures (errors against tolerances, mesh convergence, solid against
    beam) as the demo's ``validate --report`` draws them, here on one cheap case."""
    out = tmp_path / "validation"
    assert main(["validate", "--case", "torsion-fixed-free", "--quiet", "--report", str(out)]) == 0
    names = {p.name for p, _, _ in drawn}
    assert {"errors.png", "convergence.png", "solid_vs_beam.png"} <= names, names
    for path, rep, _ in drawn:
        _meets_standards(path, rep)
    assert _uncaptioned(tmp_path, "validate", "") == []


# The 3D pictures (pyvista, off screen) have no matplotlib axes: their standard is the text drawn in the
# scene -- the model's title, the mode and its frequency with its unit, and what the colour shows (the
# colour is the normalised amplitude, named in that text instead of a colour bar).

def _render_runs():
    return [pytest.param(argv, kind, id=f"render:{Path(argv[1]).name}",
                         marks=[] if Path(argv[1]).name == "cantilever.toml" else [pytest.mark.slow])
            for argv, kind in _run_list(DEMO_OUT) if argv[0] == "render"]


@pytest.mark.parametrize("argv, kind", _render_runs())
def test_demo_render_pictures_name_model_mode_and_colour(tmp_path, monkeypatch, argv, kind):
    pyvista = pytest.importorskip("pyvista")
    from fem.render import available

    if not available()[0]:
        pytest.skip("VTK cannot render off screen here")
    texts = []
    original = pyvista.Plotter.add_text

    def record(self, text, *a, **k):
        texts.append(text)
        return original(self, text, *a, **k)

    monkeypatch.setattr(pyvista.Plotter, "add_text", record)
    argv = [str(tmp_path / Path(a).relative_to(DEMO_OUT)) if a.startswith(str(DEMO_OUT)) else a for a in argv]
    if Path(argv[1]).name == "cantilever.toml":        # default tier: one mode, no animation
        argv = [a for a in argv if a != "--gif"]
        argv[argv.index("--modes") + 1] = "1"
    assert main(argv + ["--quiet"]) == 0
    pictures = sorted(Path(argv[argv.index("--render") + 1]).glob("*.png"))
    assert pictures and texts
    title = _title(Path(argv[1]).name)
    for text in texts:
        flat = " ".join(text.split())
        assert flat.startswith(title), text
        assert "mode " in flat and " Hz" in flat and "colour:" in flat, text
    assert _uncaptioned(tmp_path, "render", kind) == []
