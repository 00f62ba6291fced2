"""Programme motion: piecewise laws, standard cam laws, Fourier series, the exact follower, the cam report and
Fourier superposition of harmonic responses (discrete.motion, discrete.linear.periodic_forced)."""
import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg as sla
from scipy.interpolate import CubicSpline

from discrete.errors import ModelError
from discrete.linear.harmonic import harmonic_response
from discrete.linear.periodic_forced import PeriodicLoad, periodic_response
from discrete.lumped import Body, Link, LumpedModel
from discrete.motion import (STANDARD_LAWS, PiecewiseLaw, PiecewiseOscillator, accumulation_factor, cam_report,
                             characteristic_coefficients, discontinuity_table, dwell_rise_dwell_return, fourier_series,
                             normalised_rise, residual_factor)

ROOT = Path(__file__).resolve().parents[1]


def _fd(law, t, m, h=1e-5):
    return (law(t + h, m) - law(t - h, m)) / (2 * h)


@pytest.mark.parametrize("name", STANDARD_LAWS)
def test_standard_rise_ends_and_derivatives(name):
    s = normalised_rise(name)
    assert s(0.0) == pytest.approx(0.0, abs=1e-15)
    assert s(1.0, side="left") == pytest.approx(1.0, abs=1e-14)
    u = np.array([0.13, 0.37, 0.61, 0.88])
    for m in range(3):
        assert np.allclose(_fd(s, u, m), s(u, m + 1), rtol=1e-7, atol=1e-7)


def test_characteristic_coefficients_closed_forms():
    # cam-design closed forms: C_v, C_a, C_j
    ref = {"cycloidal": (2, 2 * math.pi, 4 * math.pi**2), "harmonic": (math.pi / 2, math.pi**2 / 2, math.pi**3 / 2),
           "polynomial345": (15 / 8, 10 / math.sqrt(3), 60.0), "constant_acceleration": (2.0, 4.0, 0.0)}
    for name, (cv, ca, cj) in ref.items():
        c = characteristic_coefficients(name)
        assert c["C_v"] == pytest.approx(cv, rel=1e-10)
        assert c["C_a"] == pytest.approx(ca, rel=1e-10)
        assert c["C_j"] == pytest.approx(cj, rel=1e-10, abs=1e-12)


def test_cycle_periodic_continuity_and_time_scaling():
    law = dwell_rise_dwell_return(0.02, 1.5, 0.7, 1.2, law="cycloidal", return_law="polynomial345")
    assert law.periodic and law.span == pytest.approx(2 * math.pi)
    assert law.continuity(3) == 2                      # jerk jumps, acceleration continuous
    assert law(2 * math.pi + 0.3) == pytest.approx(law(0.3))
    assert law(2 * math.pi, side="left") == pytest.approx(law(0.0), abs=1e-15)
    w0 = 17.0
    lt = law.in_time(w0)
    t = np.array([0.01, 0.05, 0.2, 0.33])
    for m in range(4):                                 # (2.13): x^(m) = omega0^m Pi^(m) at constant speed
        assert np.allclose(lt(t, m), w0**m * law(w0 * t, m), rtol=1e-12, atol=1e-12)
    harm = dwell_rise_dwell_return(0.02, 1.5, 0.7, 1.2, law="harmonic")
    assert harm.continuity(3) == 1


def test_ppoly_roundtrip_and_tabulated_spline():
    x = np.linspace(0, 2 * math.pi, 25)
    y = 0.01 * (1 - np.cos(x)) + 0.002 * np.sin(2 * x)
    law = PiecewiseLaw.tabulated(x, y, periodic=True)
    cs = CubicSpline(x, y, bc_type="periodic")
    t = np.linspace(0.0, 2 * math.pi, 997)[:-1]
    for m in range(3):
        assert np.allclose(law(t, m), cs(t, m), rtol=1e-12, atol=1e-14)
    assert law.continuity(3) == 2
    pp = law.to_ppoly()
    assert np.allclose(pp(t), law(t), atol=1e-15)
    back = PiecewiseLaw.from_ppoly(pp)
    assert np.array_equal(back.poly, law.poly)


def test_exogenous_form_reproduces_every_piece():
    law = dwell_rise_dwell_return(0.03, 1.0, 0.5, 1.4, law="cycloidal", return_law="harmonic").in_time(12.0)
    for i in range(law.n_pieces):
        A, e0, r = law.exogenous(i)
        for s in (0.0, 0.3 * (law.knots[i + 1] - law.knots[i])):
            e = sla.expm(A * s) @ e0
            for m in range(3):
                assert r @ np.linalg.matrix_power(A, m) @ e == pytest.approx(float(law.piece_value(i, s, m)),
                                                                           rel=1e-10, abs=1e-12)


def test_fourier_series_known_function_and_quality_figures():
    f = lambda t: 0.3 + np.cos(t) + 0.5 * np.sin(3 * t)
    fs = fourier_series(f, 2 * math.pi, 5)
    assert fs.mean == pytest.approx(0.3, abs=1e-14)
    assert np.allclose(fs.cos, [1, 0, 0, 0, 0], atol=1e-14) and np.allclose(fs.sin, [0, 0, 0.5, 0, 0], atol=1e-14)
    assert fs.max_error < 1e-13 and fs.aliasing_error < 1e-13
    saw = PiecewiseLaw([0.0, 1.0], [[0.0, 1.0]], periodic=True)
    fs = fourier_series(saw, 1.0, 20, samples=1 << 14)
    j = np.arange(1, 21)
    assert np.allclose(fs.sin, -1 / (math.pi * j), rtol=1e-4)     # DFT aliasing (pi j/N)^2/3 < 2e-5
    assert fs.mean == pytest.approx(0.5, abs=1e-12)
    assert fs.max_error > 0.04                                    # Gibbs: the jump stays visible
    assert fs.aliasing_error > 0


def test_periodic_response_equals_sum_of_harmonic_responses():
    mdl = LumpedModel(bodies=[Body("a", 1.0), Body("b", 2.0)],
                      springs=[Link(("ground", "a"), 100.0), Link(("a", "b"), 50.0)],
                      dampers=[Link(("ground", "a"), 0.4)])
    ls = mdl.linear_system()
    w = 3.0
    f = lambda t: 2.0 * np.cos(w * t) + 0.7 * np.sin(2 * w * t)
    fs = fourier_series(f, 2 * math.pi / w, 4)
    vec = np.array([0.0, 1.0])
    pr = periodic_response(ls, loads=[PeriodicLoad(vec, fs)])
    r1 = harmonic_response(ls, [w], force=2.0 * vec).response[0]
    r2 = harmonic_response(ls, [2 * w], force=-0.7j * vec).response[0]
    t = np.linspace(0, 2, 9)
    direct = (np.exp(1j * w * np.outer(t, [1, 1])) * r1).real + (np.exp(2j * w * np.outer(t, [1, 1])) * r2).real
    assert np.allclose(pr(t), direct, rtol=1e-12, atol=1e-14)
    assert pr.to_dict()["harmonics"] == 4


def test_follower_matches_table_and_runs_periodic():
    law = dwell_rise_dwell_return(0.02, math.radians(100), math.radians(60), math.radians(100), law="harmonic")
    rows = discontinuity_table(law, 20.0, 170.0)
    assert [r.order for r in rows] == [2, 2, 2, 2]
    expected = 20.0**2 * 0.02 * math.pi**2 / (2 * math.radians(100) ** 2)    # omega0^2 |Delta Pi''|
    assert all(r.extra_acceleration == pytest.approx(expected, rel=1e-12) for r in rows)
    osc = PiecewiseOscillator.follower(law.in_time(20.0), 170.0, 0.2 * 170 / (2 * math.pi))
    ss = osc.steady_state()
    assert ss.residual < 1e-12
    assert ss.ddy is not None and np.all(np.isfinite(ss.ddy))


def test_cam_report_numbers():
    law = dwell_rise_dwell_return(0.02, math.radians(100), math.radians(60), math.radians(100), law="cycloidal")
    rep = cam_report(law, 20.0, 170.0, 0.2)
    assert rep.N == pytest.approx(8.5)
    assert rep.mu == pytest.approx(0.84553, abs=5e-6)
    assert rep.continuity == 2 and {r.order for r in rep.table} == {3}
    d = rep.to_dict()
    assert d["peaks"]["Pi'"] == pytest.approx(2 * 0.02 / math.radians(100), rel=1e-9)


def test_residual_factor_and_accumulation_values():
    assert residual_factor(0.25) == pytest.approx(0.90032, abs=5e-6)
    assert residual_factor(0.0) == 1.0
    assert accumulation_factor(0.2, 9.0) == pytest.approx(1.19803, abs=5e-6)


def test_bad_input_names_the_key():
    with pytest.raises(ModelError, match="knots"):
        PiecewiseLaw([0.0, 0.0], [[1.0]])
    with pytest.raises(ModelError, match="poly"):
        PiecewiseLaw([0.0, 1.0, 2.0], [[1.0]])
    law = PiecewiseLaw([0.0, 1.0], [[0.0, 1.0]])
    with pytest.raises(ModelError, match="t = 2.0"):
        law(2.0)
    with pytest.raises(ModelError, match="side"):
        law(0.5, side="middle")
    with pytest.raises(ModelError, match="law"):
        normalised_rise("trapezoidal")
    with pytest.raises(ModelError, match="rise"):
        dwell_rise_dwell_return(0.02, -1.0, 0.0, 1.0)
    with pytest.raises(ModelError, match="rise \\+ top_dwell \\+ return"):
        dwell_rise_dwell_return(0.02, 3.0, 1.0, 3.0)
    with pytest.raises(ModelError, match="harmonics"):
        fourier_series(np.sin, 1.0, 0)
    with pytest.raises(ModelError, match="samples"):
        fourier_series(np.sin, 1.0, 10, samples=11)
    with pytest.raises(ModelError, match="law"):
        fourier_series(law, 1.0, 3)                    # not periodic
    with pytest.raises(ModelError, match="omega0"):
        cam_report(dwell_rise_dwell_return(0.02, 1.0, 0.0, 1.0), -3.0, 100.0)
    with pytest.raises(ModelError, match="law"):
        cam_report(law, 3.0, 100.0)
    with pytest.raises(ModelError, match="nu"):
        residual_factor(-0.1)
    with pytest.raises(ModelError, match="lambda"):
        accumulation_factor(-0.2, 3.0)
    with pytest.raises(ModelError, match="n = 20"):
        PiecewiseOscillator.follower(law, 10.0, 20.0)
    with pytest.raises(ModelError, match="omega0"):
        law.in_time(0.0)
    sys_ = LumpedModel(bodies=[Body("m", 1.0)], springs=[Link(("ground", "m"), 1.0)]).linear_system()
    with pytest.raises(ModelError, match="period"):
        periodic_response(sys_, loads=[PeriodicLoad(np.ones(1), fourier_series(np.sin, 2 * math.pi, 2)),
                                       PeriodicLoad(np.ones(1), fourier_series(np.sin, math.pi, 2))])
    free = LumpedModel(bodies=[Body("m", 1.0)]).linear_system()
    with pytest.raises(ModelError, match="mean"):
        periodic_response(free, loads=[PeriodicLoad(np.ones(1), fourier_series(lambda t: 1 + np.sin(t), 2 * math.pi, 2))])


def test_cam_report_example(tmp_path):
    spec = importlib.util.spec_from_file_location("cam_report_example", ROOT / "examples" / "cam_report.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    s = mod.main(tmp_path)
    assert (tmp_path / "cam_report.json").exists() and all(Path(f).exists() for f in s["figures"])
    assert s["N"] == pytest.approx(8.5)
    laws = s["laws"]
    # exact periodic follower vs Fourier superposition of the lumped follower (200 harmonics)
    assert all(d["fourier_vs_exact"] < 1e-6 for d in laws.values())
    # soft impacts of the harmonic law: Table 6.1 k^2 D = omega0^2 |Delta Pi''| = 12.958 m/s^2
    assert laws["harmonic"]["table_max_extra_acceleration"] == pytest.approx(
        20.0**2 * 0.02 * math.pi**2 / (2 * math.radians(100) ** 2), rel=1e-12)
    assert laws["harmonic"]["report"]["mu"] == pytest.approx(0.84553, abs=5e-6)
    # smoother law, smaller accompanying vibration (the book's recommendation 1)
    assert laws["cycloidal"]["max_extra_acceleration"] < laws["harmonic"]["max_extra_acceleration"]
    assert laws["harmonic"]["max_extra_acceleration"] == pytest.approx(19.55, abs=0.01)


def test_undamped_resonance_of_the_cycle_is_reported():
    from discrete.errors import SolverError

    law = dwell_rise_dwell_return(0.02, 1.5, 0.5, 1.5)
    with pytest.raises(SolverError, match="no periodic state"):
        cam_report(law, 17.0, 170.0, 0.0)          # N = k/omega0 = 10: k tau = 20 pi
