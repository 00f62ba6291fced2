"""Journal bearings and squeeze-film dampers computed from their geometry: the film solvers, the
operating point and coefficients, the linear analyses through the model file, the run-up with the
nonlinear film (the whip example, slow), the planar element in the integrators, and bad input."""
import json
import math
from pathlib import Path

import numpy as np
import pytest

from discrete.errors import ModelError
from fem.app.cli import main
from fem.rotor import Disc, Rotor, RunUp, ShaftSegment, assemble_rotor, rotor_modes, run_up, stability_threshold
from fem.rotor.bearings.journal import JournalBearing
from fem.rotor.bearings.reynolds import ReynoldsFilm
from fem.rotor.bearings.short_film import ShortFilm
from fem.rotor.bearings.squeeze_film import SqueezeFilmDamper
from fem.sections import Material

EX = Path(__file__).resolve().parent.parent / "examples"
MASSLESS = Material(E=211e9, G=81.2e9, rho=0.0)


def _bearing(**kw):
    args = dict(x=0.0, diameter=0.05, length=0.0125, clearance=50e-6, viscosity=0.01, load=100.0, film="short",
                speeds=[300.0, 600.0, 900.0])
    return JournalBearing(**(args | kw))


# ---------------------------------------------------------------- films
def test_cavitation_solution_is_complementary():
    """Reynolds' condition: P >= 0, the film equation holds where P > 0 and its residual is >= 0 where P = 0."""
    film = ReynoldsFilm(0.5, 36, 6)
    sol = film.solve(0.6, 0.1, -3.6, 0.6)
    A = film.matrix(0.6, 0.1)
    lam = A @ sol.P - film.source(-3.6, 0.6)
    scale = np.abs(film.source(-3.6, 0.6)).max()
    assert sol.P.min() >= 0
    assert np.abs(lam[sol.wet]).max() < 1e-10 * scale
    assert lam[~sol.wet].min() > -1e-10 * scale
    assert 0 < sol.wet.mean() < 1


@pytest.mark.parametrize("cavitation", ["reynolds", "gumbel"])
def test_film_derivatives_match_finite_differences(cavitation):
    """The discrete perturbation (wet set held) against central differences of the solved force."""
    film = ReynoldsFilm(0.5, 48, 8, cavitation)
    x = np.array([0.4, -0.3, -2.4, -1.8])
    J = film.derivatives(film.solve(*x))
    for j, h in enumerate((1e-6, 1e-6, 1e-5, 1e-5)):
        up, dn = x.copy(), x.copy()
        up[j] += h
        dn[j] -= h
        fd = (film.force(*up) - film.force(*dn)) / (2 * h)
        assert np.allclose(J[:, j], fd, rtol=2e-4, atol=1e-7 * np.abs(J).max())


def test_short_film_is_rotation_equivariant_and_matches_ocvirk():
    f = ShortFilm(0.25)
    e, LR = 0.5, 0.5
    Fr, Ft = LR ** 3 * e ** 2 / (1 - e ** 2) ** 2, math.pi * LR ** 3 * e / (4 * (1 - e ** 2) ** 1.5)
    assert np.allclose(f.force(e, 0.0, -6 * e, 0.0), [-Fr, Ft], rtol=1e-13)
    a = 0.8
    R = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    X = R @ np.array([0.3, 0.2])
    ba = R @ np.array([1.1, -0.7])                  # g = a sin + b cos: (b, a) turns like a vector
    assert np.allclose(f.force(*X, ba[1], ba[0]), R @ f.force(0.3, 0.2, -0.7, 1.1), rtol=1e-12)


def test_film_refuses_a_closed_film():
    with pytest.raises(Exception, match="eccentricity ratio"):
        ShortFilm(0.25).force(1.0, 0.0, -6.0, 0.0)


# ---------------------------------------------------------------- operating point
def test_operating_point_balances_the_load_and_rotates_with_it():
    b = _bearing(film="reynolds", mesh=(72, 8))
    st = b.operating_point(600.0)
    F = b.force_scale * 600.0 * b.film_model().force(*(st.position / b.clearance), -6 * st.position[0] / b.clearance,
                                                     6 * st.position[1] / b.clearance)
    assert np.allclose(F, -b.static_load(), rtol=1e-9, atol=1e-9 * b.load)
    assert 0 < st.attitude_deg < 90 and 0 < st.eccentricity < 1
    side = _bearing(film="reynolds", mesh=(72, 8), load_angle=0.0)
    st2 = side.operating_point(600.0)
    assert st2.eccentricity == pytest.approx(st.eccentricity, rel=1e-9)
    assert st2.attitude_deg == pytest.approx(st.attitude_deg, rel=1e-9)
    # the damping matrix of a film is symmetric, the stiffness is not
    assert st.C[0, 1] == pytest.approx(st.C[1, 0], rel=1e-8)
    assert abs(st.K[0, 1] - st.K[1, 0]) > 0.1 * abs(st.K).max()


def test_sommerfeld_scaling():
    """Doubling speed and load leaves the eccentricity; the coefficients scale with the load."""
    b1, b2 = _bearing(load=100.0), _bearing(load=200.0)
    s1, s2 = b1.operating_point(300.0), b2.operating_point(600.0)
    assert s1.sommerfeld == pytest.approx(s2.sommerfeld, rel=1e-14)
    assert s1.eccentricity == pytest.approx(s2.eccentricity, rel=1e-9)
    assert np.allclose(s2.K, 2 * s1.K, rtol=1e-7)
    assert np.allclose(s2.C, s1.C, rtol=1e-7)


def test_too_slow_for_the_load_is_a_clear_error():
    b = _bearing(load=1e5)
    with pytest.raises(ModelError) as e:
        b.operating_point(300.0)
    assert e.value.key == "speeds" and "eccentricity ratio" in e.value.allowed


@pytest.mark.parametrize("kw, key", [({"diameter": 0.0}, "diameter"), ({"clearance": 0.01}, "clearance"),
                                     ({"film": "long"}, "film"), ({"speeds": [0.0, 100.0]}, "speeds"),
                                     ({"speeds": None}, "speeds"), ({"mesh": (8, 2)}, "mesh"),
                                     ({"grooves": ((0.0, 0.3),)}, "grooves"), ({"kyy": 1e6}, "kyy"),
                                     ({"load": -1.0}, "load")])
def test_journal_bearing_rejects_bad_values(kw, key):
    rotor_args = dict(discs=[Disc(0.25, 10.0)])
    with pytest.raises(ModelError) as e:
        Rotor([ShaftSegment(0.5, 2, 0.05, MASSLESS)], bearings=[_bearing(**kw), _bearing(x=0.5)], **rotor_args)
    assert e.value.key == key
    assert e.value.where.startswith("[[rotor.journal_bearing]] #1")


def test_weight_share_and_linear_analyses():
    """Two bearings carry the weight of the disc and journals; modal and threshold run on the table."""
    grid = list(np.linspace(400.0, 1500.0, 23))
    b = [JournalBearing(x, diameter=0.05, length=0.0125, clearance=50e-6, viscosity=0.01, film="short", speeds=grid)
         for x in (0.0, 0.5)]
    rotor = Rotor([ShaftSegment(0.5, 2, 0.05, MASSLESS)], discs=[Disc(0.0, 4.0), Disc(0.25, 20.0), Disc(0.5, 4.0)],
                  bearings=b)
    rs = assemble_rotor(rotor)
    assert np.allclose(b[0].static_load(), [0.0, -14.0 * 9.81], atol=1e-9)
    m = rotor_modes(rs, 800.0, 4)
    assert np.all(np.isfinite(m.eigenvalues))
    thr = stability_threshold(rs, 1500.0, 4, speed_min=450.0, n_grid=12)
    assert thr.threshold_rad_s == pytest.approx(1019.79, rel=2e-4)            # closed form: the validation case


def test_speed_outside_the_table_names_the_journal_bearing():
    b = [_bearing(x=x, load=None) for x in (0.0, 0.5)]
    rotor = Rotor([ShaftSegment(0.5, 2, 0.05, MASSLESS)], discs=[Disc(0.25, 10.0)], bearings=b)
    with pytest.raises(ModelError) as e:
        rotor_modes(rotor, 100.0, 2)
    assert e.value.where == "[[rotor.journal_bearing]] #1" and e.value.key == "speed"


# ---------------------------------------------------------------- squeeze-film damper
def test_damper_linearisation_is_half_the_full_film():
    kw = dict(diameter=0.1, length=0.01, clearance=1e-4, viscosity=0.02, centering_stiffness=2e6, load=50.0)
    pi = SqueezeFilmDamper(0.0, film="pi", **kw)
    full = SqueezeFilmDamper(0.0, film="2pi", **kw)
    assert np.allclose(pi.damping_matrix(), 0.5 * full.damping_matrix(), rtol=1e-6)
    with pytest.raises(ModelError) as e:
        SqueezeFilmDamper(0.0, film="pi", **(kw | {"load": 500.0})).check("[[rotor.squeeze_film_damper]] #1")
    assert e.value.key == "load"


# ---------------------------------------------------------------- run-ups
def _jeffcott(journal_mass=4.0):
    grid = list(np.linspace(600.0, 1500.0, 46))
    b = [JournalBearing(x, diameter=0.05, length=0.0125, clearance=50e-6, viscosity=0.01, film="short", speeds=grid)
         for x in (0.0, 0.5)]
    return Rotor([ShaftSegment(0.5, 2, 0.05, MASSLESS)], discs=[Disc(0.0, journal_mass), Disc(0.25, 20.0),
                                                                 Disc(0.5, journal_mass)], bearings=b)


def test_steady_start_sits_at_the_operating_point():
    """start = 'steady' below the threshold: the journals stay at the bearings' operating point."""
    rotor = _jeffcott()
    res = run_up(rotor, RunUp(800.0, 800.0, 0.05, modes=6, start="steady"), [], probes=[0.0])
    st = rotor.bearings[0].operating_point(800.0)
    assert np.allclose([res.orbit_y[-1, 0], res.orbit_z[-1, 0]], st.position, rtol=1e-6, atol=1e-6 * 50e-6)
    assert res.integrator == "LSODA" and res.works["static_load"] != 0.0 and "bearings" in res.works
    assert res.bearings[0].eccentricity[-1] == pytest.approx(st.eccentricity, rel=1e-6)


def test_moreau_takes_the_film_explicitly():
    rotor = _jeffcott(journal_mass=4.0)
    ev = run_up(rotor, RunUp(800.0, 800.0, 0.01, modes=6, start="steady"), [], probes=[0.25])
    mj = run_up(rotor, RunUp(800.0, 800.0, 0.01, modes=6, start="steady", method="moreau", time_step=4e-6), [],
                probes=[0.25])
    assert np.allclose(mj.orbit_z[-1], ev.orbit_z[-1], rtol=1e-4)


def test_whip_example_campbell_and_file_bad_input(tmp_path):
    j = tmp_path / "c.json"
    assert main(["campbell", str(EX / "rotor_journal_whip.toml"), "--json", str(j)]) == 0
    d = json.loads(j.read_text())
    ld = np.array([[np.nan if v is None else v for v in col] for col in d["log_decrement"]])
    assert (ld[:, 0] > 0).any() and (np.nanmin(ld[:, -1]) < 0)     # a mode turns unstable within the range
    f = tmp_path / "f.json"
    assert main(["forced", str(EX / "rotor_journal_whip.toml"), "--json", str(f)]) == 0
    peaks = json.loads(f.read_text())["peaks"]
    assert peaks and 3000 < peaks[0]["speed_rad_s"] * 30 / math.pi < 9000     # the first critical, on the films
    bad = (EX / "rotor_journal_whip.toml").read_text().replace("viscosity = 0.01", "viscosity = -0.01", 1)
    p = tmp_path / "bad.toml"
    p.write_text(bad)
    assert main(["campbell", str(p)]) == 2


@pytest.mark.slow
def test_whip_example_runup_onset(tmp_path):
    """The example's run-up: the whirl onset within 2 % of the linear threshold of the same rotor."""
    out = tmp_path / "sim.json"
    assert main(["simulate", str(EX / "rotor_journal_whip.toml"), "--json", str(out), "--png", str(tmp_path)]) == 0
    d = json.loads(out.read_text())
    from fem.study import Study

    rs = Study.load(EX / "rotor_journal_whip.toml").rotor
    thr = stability_threshold(rs, 15000 * math.pi / 30, 4, speed_min=3000 * math.pi / 30, n_grid=25)
    assert d["whirl"]["onset_speed_rad_s"] == pytest.approx(thr.threshold_rad_s, rel=0.02)
    assert d["whirl"]["onset_speed_rad_s"] == pytest.approx(987.37, rel=1e-3)
    assert d["whirl"]["whirl_frequency_rad_s"] == pytest.approx(thr.frequency_rad_s, rel=0.01)
    assert d["whirl"]["final_ratio"] < 0.55 and d["whirl"]["growth"] > 100
    assert d["energy"]["relative_error"] < 1e-4
    assert (tmp_path / "cascade.png").exists() and (tmp_path / "whirl_onset.png").exists()


def test_bearing_on_a_pedestal_and_a_rub_in_one_run():
    """A journal bearing on a pedestal acts on the relative motion (its reaction moves the pedestal), and a
    rub ring works alongside the films in the same run."""
    from fem.rotor import Pedestal, Rub, Unbalance

    grid = list(np.linspace(600.0, 1500.0, 19))
    b = [JournalBearing(0.0, diameter=0.05, length=0.0125, clearance=50e-6, viscosity=0.01, film="short",
                        speeds=grid, pedestal="housing"),
         JournalBearing(0.5, diameter=0.05, length=0.0125, clearance=50e-6, viscosity=0.01, film="short", speeds=grid)]
    rotor = Rotor([ShaftSegment(0.5, 2, 0.05, MASSLESS)], discs=[Disc(0.0, 4.0), Disc(0.25, 20.0), Disc(0.5, 4.0)],
                  bearings=b, pedestals=[Pedestal("housing", 10.0, 5e7, 5e7, 1e3, 1e3)])
    res = run_up(rotor, RunUp(800.0, 800.0, 0.01, modes=8, start="steady"), [Unbalance(0.25, 1e-4)],
                 [Rub(0.25, 25e-6, stiffness=1e7, friction=0.1)], probes=[0.0])
    st = b[0].operating_point(800.0)
    hist = res.bearings[0]
    assert res.stopped is None
    assert hist.eccentricity[0] == pytest.approx(st.eccentricity, rel=5e-2)    # plus the synchronous orbit
    rs = assemble_rotor(rotor)
    iv = int(np.flatnonzero(rs.dof_field == "pedestal_w")[0])
    assert iv >= 0 and res.rubs[0].contact_phases >= 1
    assert abs(res.energy_error) < 1e-4
