"""drivefem convert (ROSS rotor files), layered sections and speed-table extrapolation."""
from __future__ import annotations

import json
import warnings
from pathlib import Path

import numpy as np
import pytest
import tomli_w

from discrete.errors import ModelError
from fem.app.cli import main
from fem.rotor import Bearing, Layer, Rotor, ShaftSegment, assemble_rotor, rotor_modes, rpm
from fem.sections import Material

ROOT = Path(__file__).resolve().parent.parent
DATA = ROOT / "validation" / "data" / "ross"
STEEL = Material(E=211e9, G=81.2e9, rho=7810.0)


def test_convert_friswell_and_run(tmp_path, capsys):
    out = tmp_path / "f.toml"
    assert main(["convert", str(DATA / "friswell_damped.toml"), "--out", str(out)]) == 0
    assert "6 elements in 1 segments" in capsys.readouterr().out
    j = tmp_path / "m.json"
    text = out.read_text()
    out.write_text(text + '\n[analysis]\nspeed_rpm = 4000\nmodes = 14\n')
    assert main(["modal", str(out), "--json", str(j)]) == 0
    ref = json.loads((DATA / "friswell.json").read_text())["damped"]["modal_4000rpm"]
    ours = np.asarray(json.loads(j.read_text())["omega_rad_s"])
    for w in ref["wd"]:
        assert np.min(np.abs(ours - w)) / w < 1e-9


def test_example_matches_ross_at_4000_rpm(capsys):
    """examples/ross_compressor.toml (ROSS's table convention): ROSS's damped frequencies and log
    decrements at 4000 rev/min as ROSS computes them (its smoothing spline)."""
    from fem.modelfile.build.rotor import rotor_model
    from fem.study import Study

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        rotor = rotor_model(Study.load(ROOT / "examples" / "ross_compressor.toml").doc)
        m = rotor_modes(rotor, rpm(4000), 12)
    ref = json.loads((DATA / "compressor.json").read_text())["modal_4000rpm_as_is"]
    osc = m.eigenvalues[m.eigenvalues.imag > 1e-9]
    for w, ld in zip(ref["wd"][:5], ref["log_dec"][:5]):
        k = np.argmin(np.abs(osc.imag - w))
        assert abs(osc[k].imag - w) / w < 1e-6
        assert abs(-2 * np.pi * osc[k].real / osc[k].imag - ld) < 1e-6
    assert sum(len(s.layers) for s in rotor.segments) == 36


@pytest.mark.parametrize("edit, pattern", [
    (lambda d: d["ShaftElement_ShaftElement 0"].update(shear_effects=False), "shear_effects = False"),
    (lambda d: d["ShaftElement_ShaftElement 0"].update(axial_force=1e3), "axial_force = 1000"),
    (lambda d: d.update({"MagneticBearingElement_x": {"n": 0, "kxx": 1.0, "cxx": 0.0}}), "MagneticBearingElement"),
    (lambda d: d["BearingElement_Bearing 0"].update(mxx=[1.0] * 8), "mxx = 1.0"),
    (lambda d: d.update({"GearElement_g": {"n": 3}}), "not supported: GearElement"),
])
def test_unsupported_ross_content_is_refused(tmp_path, capsys, edit, pattern):
    import tomllib

    d = tomllib.loads((DATA / "compressor_example.toml").read_text())
    edit(d)
    src = tmp_path / "r.toml"
    src.write_text(tomli_w.dumps(d))
    assert main(["convert", str(src), "--out", str(tmp_path / "o.toml")]) == 2
    err = capsys.readouterr().err
    assert pattern in err and "Traceback" not in err, err
    assert not (tmp_path / "o.toml").exists()


def test_not_a_ross_file(tmp_path, capsys):
    assert main(["convert", str(ROOT / "examples" / "rotor_friswell.toml")]) == 2
    assert "ShaftElement" in capsys.readouterr().err
    assert main(["convert", str(tmp_path / "missing.toml")]) == 2


# ------------------------------------------------------------------ layers
def _shaft(layers=(), n=4):
    return Rotor([ShaftSegment(1.2, n, 0.05, STEEL, layers=list(layers))],
                 bearings=[Bearing(0.0, kyy=1e6, kzz=1e6), Bearing(1.2, kyy=1e6, kzz=1e6)], dofs="full")


def test_mass_only_layer_adds_inertia_not_stiffness():
    bare = assemble_rotor(_shaft())
    sleeve = assemble_rotor(_shaft([Layer(0.09, 0.05, STEEL, mass_only=True)]))
    assert abs(sleeve.K0 - bare.K0).max() == 0.0
    assert sleeve.total_mass() == pytest.approx(bare.total_mass() + STEEL.rho * np.pi * (0.09**2 - 0.05**2) / 4 * 1.2,
                                                rel=1e-13)
    assert abs(sleeve.G).max() > abs(bare.G).max()            # polar inertia: gyroscopic terms grow
    structural = assemble_rotor(_shaft([Layer(0.09, 0.05, STEEL)]))
    assert abs(structural.K0 - bare.K0).max() > 0


@pytest.mark.parametrize("layer, key", [
    (Layer(0.09, 0.04, STEEL), "di"),                         # overlaps the shaft (d = 0.05)
    (Layer(0.04, 0.05, STEEL), "di"),                         # bore above the outer diameter
    (Layer(0.09, 0.05, STEEL, shear_coefficient=2.0), "shear_coefficient"),
])
def test_bad_layers(layer, key):
    with pytest.raises(ModelError) as err:
        _shaft([layer])
    assert err.value.key == key


# ------------------------------------------------------------------ extrapolation
def _tabled(extrapolate, interpolation="linear"):
    b = Bearing(0.0, kyy=[1e6, 2e6, 4e6], kzz=1e6, cyy=[100.0, 90.0, 60.0], czz=50.0, speeds=[100.0, 200.0, 300.0],
                extrapolate=extrapolate, interpolation=interpolation, name="tilting pad")
    return assemble_rotor(Rotor([ShaftSegment(1.2, 4, 0.05, STEEL)], bearings=[b, Bearing(1.2, kyy=1e6, kzz=1e6)]))


def test_extrapolation_hold_linear_refuse():
    with pytest.raises(ModelError, match="inside the bearing table"):
        _tabled("refuse").coefficients([50.0])
    with pytest.warns(UserWarning, match=r"#1 'tilting pad' at x = 0 m: speeds 0 \.\.\. 100 rad/s below and 300 \.\.\. 400 rad/s above its table"):
        c = _tabled("hold").coefficients([0.0, 400.0])
    assert c[0, 0] == 1e6 and c[1, 0] == 4e6
    with pytest.warns(UserWarning, match="extrapolated linearly"):
        c = _tabled("linear").coefficients([0.0, 400.0])
    assert c[0, 0] == pytest.approx(0.0, abs=1e-6) and c[1, 0] == pytest.approx(6e6, rel=1e-12)
    assert c[0, 4] == pytest.approx(110.0, rel=1e-12)
    with pytest.raises(ModelError, match="extrapolated speed"):               # damping would turn negative
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            _tabled("linear").coefficients([600.0])


def test_spline_extrapolates_along_its_end_tangent():
    from scipy.interpolate import CubicSpline

    rs = _tabled("linear", "spline")
    t = rs.tables[0]
    spline = CubicSpline([100.0, 200.0, 300.0], [1e6, 2e6, 4e6])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        c = rs.coefficients([50.0, 150.0])
    assert c[1, 0] == pytest.approx(float(spline(150.0)), rel=1e-12)
    assert c[0, 0] == pytest.approx(1e6 - 50.0 * float(spline(100.0, 1)), rel=1e-12)
    assert t.extrapolate == "linear"


# ------------------------------------------------------------------ ROSS's table convention
def _ross_spline(grid, row):
    """ROSS 2.3.0's _process_coefficient, written out (UnivariateSpline; interp1d for 2-3 points)."""
    from scipy import interpolate

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            return interpolate.UnivariateSpline(grid, row)
        except Exception:
            return interpolate.interp1d(grid, row, kind=len(grid) - 1, fill_value="extrapolate")


@pytest.mark.parametrize("n", [2, 3, 4, 7])
def test_smoothing_spline_is_ross_interpolation(n):
    grid = np.linspace(400.0, 1200.0, n)
    kyy = 1e7 * (1.0 + 0.3 * np.sin(grid / 300.0)) + 2e5 * np.cos(grid / 37.0)
    cyy = 5e3 + 2.0 * grid
    b = Bearing(0.0, kyy=kyy.tolist(), kzz=1e6, cyy=cyy.tolist(), czz=50.0, speeds=grid.tolist(),
                interpolation="smoothing-spline", extrapolate="continue", name="pad")
    rs = assemble_rotor(Rotor([ShaftSegment(1.2, 4, 0.05, STEEL)], bearings=[b, Bearing(1.2, kyy=1e6, kzz=1e6)]))
    s = np.array([0.0, 250.0, 400.0, 555.5, 1000.0, 1200.0, 1500.0])
    with pytest.warns(UserWarning, match="end cubics .ROSS's convention."):
        c = rs.coefficients(s)
    for j, row in ((0, kyy), (4, cyy)):
        ross = _ross_spline(grid, row)(s)
        assert np.max(np.abs(c[:, j] - ross)) <= 1e-13 * np.abs(ross).max()
    # a constant (ROSS spreads it over the speeds and fits it too): the constant to round-off
    assert np.max(np.abs(c[:, 3] - _ross_spline(grid, np.full(n, 1e6))(s))) <= 1e-9
    assert np.max(np.abs(c[:, 3] - 1e6)) <= 1e-12 * 1e6


def test_smoothing_spline_misses_its_points_and_other_extrapolations():
    grid = np.linspace(400.0, 1200.0, 6)
    kyy = 1e7 + np.array([0.0, 3e5, -2e5, 4e5, 1e5, -3e5])
    common = dict(kzz=1e6, czz=50.0, speeds=grid.tolist(), interpolation="smoothing-spline")
    rs = {e: assemble_rotor(Rotor([ShaftSegment(1.2, 4, 0.05, STEEL)], bearings=[
        Bearing(0.0, kyy=kyy.tolist(), extrapolate=e, **common), Bearing(1.2, kyy=1e6, kzz=1e6)]))
          for e in ("refuse", "hold", "linear", "continue")}
    inside = rs["refuse"].coefficients(grid)[:, 0]
    assert 0 < np.max(np.abs(inside - kyy)) < 1e-1 * 1e7         # a smoothing spline, not an interpolant
    with pytest.raises(ModelError, match="inside the bearing table"):
        rs["refuse"].coefficients([100.0])
    spline = _ross_spline(grid, kyy)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        hold = rs["hold"].coefficients([100.0, 2000.0])[:, 0]
        lin = rs["linear"].coefficients([100.0])[0, 0]
        cont = rs["continue"].coefficients([100.0])[0, 0]
    assert hold == pytest.approx([float(spline(400.0)), float(spline(1200.0))], rel=1e-14)
    assert lin == pytest.approx(float(spline(400.0) - 300.0 * spline.derivative()(400.0)), rel=1e-13)
    assert cont == pytest.approx(float(spline(100.0)), rel=1e-13) and abs(cont - lin) > 1.0


def test_continue_with_linear_interpolation_is_linear():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        a = _tabled("continue").coefficients([0.0, 50.0, 150.0, 400.0])
        b = _tabled("linear").coefficients([0.0, 50.0, 150.0, 400.0])
    assert np.array_equal(a, b)


def test_smoothing_spline_damping_must_stay_dissipative():
    """The smoothing spline leaves the checked table values: its damping is checked where used."""
    grid = [100.0, 200.0, 300.0, 400.0, 500.0]
    b = Bearing(0.0, kyy=1e6, kzz=1e6, cyy=[0.0, 0.0, 1e3, 0.0, 0.0], czz=50.0, speeds=grid,
                interpolation="smoothing-spline", name="bad seal")
    rs = assemble_rotor(Rotor([ShaftSegment(1.2, 4, 0.05, STEEL)], bearings=[b, Bearing(1.2, kyy=1e6, kzz=1e6)]))
    with pytest.raises(ModelError, match="smoothing spline does not pass through"):
        rs.coefficients(np.linspace(100.0, 500.0, 41))


def test_convert_writes_ross_convention_by_default(tmp_path, capsys):
    out = tmp_path / "c.toml"
    assert main(["convert", str(DATA / "compressor_example.toml"), "--out", str(out)]) == 0
    text = out.read_text()
    assert text.count('interpolation = "smoothing-spline"') == 14 and text.count('extrapolate = "continue"') == 14
    assert "It is not an interpolant" in text and "misses" in text
    assert main(["convert", str(DATA / "compressor_example.toml"), "--out", str(out), "--interpolation", "spline",
                 "--extrapolate", "linear"]) == 0
    text = out.read_text()
    assert text.count('interpolation = "spline"') == 14 and text.count('extrapolate = "linear"') == 14
    assert main(["convert", str(DATA / "compressor_example.toml"), "--out", str(out), "--interpolation", "linear"]) == 0
    assert out.read_text().count('extrapolate = "refuse"') == 14


def test_compressor_example_script(tmp_path):
    """examples/ross_compressor.py: ROSS's tables from rest; no critical speed at rest (four bearing
    modes are overdamped there), the 1x crossings of the first backward/forward pair near 9650 and
    9960 rev/min; the figure is written."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("ross_compressor_example", ROOT / "examples" / "ross_compressor.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    modes, camp, shown, path = mod.run(tmp_path)
    assert path.exists() and path.stat().st_size > 10_000
    assert np.sum(camp.omega_damped_rad_s[0] == 0) == 6                 # 2 rigid + 4 overdamped bearing modes
    crit = [c for c in camp.crossings if c.log_decrement < 5]
    assert all(c.speed_rpm > 1000 for c in camp.crossings)
    assert [round(c.speed_rpm) for c in crit] == [9648, 9962]
    assert [c.whirl for c in crit] == ["backward", "forward"]
    assert 9962 in [round(c.speed_rpm) for c in camp.critical_speeds]          # the forward one is a critical speed
    assert 9648 in [round(c.speed_rpm) for c in camp.backward_crossings]
