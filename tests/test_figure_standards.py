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
