"""Rotor-stator rub and bearing clearance: the radial contact law, the run-up example through the CLI
(its numbers asserted), the two integrators' reports, and bad input (clear errors, exit code 2)."""
import json
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from discrete.errors import ModelError
from discrete.nonsmooth.elements.radial import RadialClearance
from fem.app.cli import main
from fem.rotor import Bearing, Disc, Rotor, Rub, RunUp, ShaftSegment, Support, Unbalance, run_up
from fem.sections import Material

EX = Path(__file__).resolve().parent.parent / "examples"
STEEL = Material(E=211e9, G=81.2e9, rho=7810.0)
MASSLESS = Material(E=211e9, G=81.2e9, rho=0.0)


def _ring(**kw):
    args = dict(name="r", g_y=np.array([1.0, 0.0]), g_z=np.array([0.0, 1.0]), clearance=1e-3)
    return RadialClearance(**(args | kw))


# ---------------------------------------------------------------- the law
@pytest.mark.parametrize("kw, key", [({"clearance": 0.0}, "clearance"), ({"stiffness": -1.0}, "stiffness"),
                                     ({"restitution": 1.5}, "restitution"), ({"friction": -0.1}, "friction"),
                                     ({"friction": 0.2}, "radius"), ({"centre": (2e-3, 0.0)}, "centre"),
                                     ({"centre": (0.0,)}, "centre"), ({"damping": float("nan")}, "damping")])
def test_ring_rejects_bad_values(kw, key):
    with pytest.raises(ModelError) as e:
        _ring(**kw)
    assert e.value.key == key


def test_compliant_force_normal_and_friction():
    c = _ring(stiffness=1e6, damping=10.0, friction=0.2, radius=0.02)
    y, z, yd, zd = 1.5e-3, 0.0, 0.1, 0.3            # outward 0.5 mm, moving outward 0.1 m/s, tangentially 0.3 m/s
    Fy, Fz, N, vs = c.force(y, z, yd, zd, 100.0, 1.0)
    assert N == pytest.approx(1e6 * 0.5e-3 + 10.0 * 0.1)
    assert vs == pytest.approx(0.3 + 100.0 * 0.02)          # t = (0, 1) at n = (1, 0)
    assert Fy == pytest.approx(-N) and Fz == pytest.approx(-0.2 * N)
    assert c.potential(y, z) == pytest.approx(0.5 * 1e6 * 0.25e-6)


def _consistent(c, W, U_free, un0, P, case):
    """Newton + Coulomb after the step: complementarity and the cone."""
    U = U_free + W @ P
    target = -c.restitution * min(un0, 0.0)
    tol = 1e-9 * (1 + np.abs(U_free).max())
    assert P[0] >= -tol and U[0] >= target - tol
    assert abs(P[0] * (U[0] - target)) <= tol * (1 + abs(P[0]))
    assert abs(P[1]) <= c.friction * P[0] + tol
    if case == "slip":
        assert P[1] * U[1] <= tol and abs(abs(P[1]) - c.friction * P[0]) <= tol
    if case == "stick":
        assert abs(U[1]) <= tol


def test_rigid_impulse_solves_the_local_problem_exactly():
    c = _ring(friction=0.3, radius=0.02, restitution=0.4)
    rng = np.random.default_rng(3)
    seen = set()
    for _ in range(400):
        A = rng.normal(size=(2, 2))
        W = A @ A.T + 0.1 * np.eye(2) + 0.2 * np.array([[0.0, 1.0], [-1.0, 0.0]]) * rng.normal()
        U_free = rng.normal(size=2)
        un0 = rng.normal()
        P, case = c.impulse(W, U_free, un0)
        seen.add(case)
        if case != "paradox":
            _consistent(c, W, U_free, un0, P, case)
    assert {"free", "stick", "slip"} <= seen


# ---------------------------------------------------------------- the example through the CLI
def test_rub_runup_example(tmp_path, capsys):
    """examples/rotor_rub_runup.toml: partial rub from ~805 rev/min, full annular rub ~945-1300 rev/min,
    the energy balance closed, the reduced rotor exact at the seal's statics; JSON, CSV and plots."""
    j, csv, png = tmp_path / "r.json", tmp_path / "r.csv", tmp_path / "png"
    assert main(["simulate", str(EX / "rotor_rub_runup.toml"), "--json", str(j), "--csv", str(csv),
                 "--png", str(png)]) == 0
    text = capsys.readouterr().out
    assert "full annular rub at rev/min" in text and "balance error" in text
    d = json.loads(j.read_text())
    assert d["schema"] == "drivefem.simulate" and d["kind"] == "rotor" and d["stopped"] is None
    rub = d["rubs"][0]
    rpm = 30 / math.pi
    assert rub["first_contact"]["speed_rad_s"] * rpm == pytest.approx(805, abs=5)
    (a, b), *_ = rub["full_annular_rub"]
    t, s = np.array(d["samples"]["t"]), np.array(d["samples"]["speed_rad_s"])
    assert np.interp(a, t, s) * rpm == pytest.approx(945, abs=10)
    assert np.interp(b, t, s) * rpm == pytest.approx(1299, abs=10)
    assert rub["max_normal_force"] == pytest.approx(74.05, rel=2e-3)
    assert d["energy"]["relative_error"] < 1e-9
    assert d["energy"]["works"]["friction"] < 0 and d["energy"]["works"]["spin_friction"] < 0
    assert np.allclose(d["reduction"]["restitution"], 1.0, atol=1e-9)
    assert d["reduction"]["frequency_check"]["max_relative_error"] < 2e-3
    assert csv.read_text().splitlines()[0].startswith("t,speed_rad_s")
    assert (png / "run_up.png").stat().st_size > 10_000 and (png / "run_up_orbits.png").is_file()


# ---------------------------------------------------------------- the integrators' reports
def _jeffcott(zeta=0.02):
    L, m = 0.8, 10.0
    k = 48 * 211e9 * math.pi * 0.03 ** 4 / 64 / L ** 3            # Euler-Bernoulli estimate: only a scale here
    c = 2 * zeta * math.sqrt(k * m)
    return Rotor([ShaftSegment(L, 4, 0.03, MASSLESS)], discs=[Disc(L / 2, m)], supports=[Support(0.0), Support(L)],
                 bearings=[Bearing(L / 2, cyy=c, czz=c)]), math.sqrt(k / m)


def test_slip_reversal_stops_the_compliant_run_and_says_why():
    """mu = 0.1 on a soft ring drives backward whirl (friction-induced): the slip velocity reaches zero,
    which the compliant law does not model; the run stops there with the reason, exit code 1."""
    rotor, w = _jeffcott()
    res = run_up(rotor, RunUp(1.2 * w, 1.2 * w, 2.0, modes=2), [Unbalance(0.4, 1e-3)],
                 [Rub(0.4, 2e-4, stiffness=2 * 10 * w * w, friction=0.1, radius=0.015)])
    assert res.stopped and "slip velocity" in res.stopped and "moreau" in res.stopped
    assert res.events[-1]["kind"] == "slip_reversal"
    assert res.works["friction"] > 0            # the friction feeds the backward whirl
    assert res.energy_error < 100 * RunUp.rtol  # the balance integrates with the state at rtol 1e-8


def test_moreau_on_a_rigid_ring_settles_in_forward_annular_rub():
    """The same rotor on a rigid ring (Moreau-Jean, restitution 0, mu = 0.5): the orbit is held on the
    ring, so the backward whirl cannot grow; one contact, then a full annular rub with forward slip
    (Omega R + whirl speed), friction dissipating, the discrete energy identity closed."""
    rotor, w = _jeffcott()
    res = run_up(rotor, RunUp(1.2 * w, 1.2 * w, 2.0, modes=2, method="moreau", start="rest"),
                 [Unbalance(0.4, 1e-3)], [Rub(0.4, 2e-4, friction=0.5, radius=0.015, restitution=0.0)])
    rub = res.rubs[0]
    assert res.stopped is None and res.energy_error < 1e-10
    assert [e["kind"] for e in res.events] == ["contact"]
    assert rub.slip[-1] == pytest.approx(1.2 * w * (0.015 + 2e-4), rel=1e-3)     # first-order scheme: ~1e-4
    assert rub.regime[-1] == "full" and res.works["friction"] < 0
    assert np.hypot(res.orbit_y[-1, 0], res.orbit_z[-1, 0]) == pytest.approx(2e-4, rel=1e-9)


def test_speed_dependent_bearings_parametric_work_and_free_rotor():
    """A ramp across tabulated bearings: their stiffness change is the work 'parametric' and the balance
    closes; a rotor without supports runs on its rigid-body modes with a warning (no attachment
    shapes, restitution not defined)."""
    L = 1.0
    brg = dict(speeds=[0.0, 400.0], kyy=[1e6, 3e6], kzz=[1e6, 3e6], cyy=[500.0, 500.0], czz=[500.0, 500.0])
    rotor = Rotor([ShaftSegment(L, 6, 0.04, STEEL)], discs=[Disc(0.5, 8.0, 0.02, 0.04)],
                  bearings=[Bearing(0.0, **brg), Bearing(L, **brg)])
    res = run_up(rotor, RunUp(50.0, 350.0, 0.3, modes=8), [Unbalance(0.5, 1e-4)], [Rub(0.5, 1e-3, stiffness=1e6)])
    assert res.works["parametric"] != 0.0 and res.energy_error < 1e-8
    free = Rotor([ShaftSegment(L, 6, 0.04, STEEL)], discs=[Disc(0.5, 8.0, 0.02, 0.04)])
    res = run_up(free, RunUp(10.0, 50.0, 0.2, modes=6), [Unbalance(0.5, 1e-4)], [Rub(0.5, 1e-3, stiffness=1e6)])
    assert any("rigid-body" in w for w in res.warnings) and res.reduction["restitution"] == [None, None]


# ---------------------------------------------------------------- bad input
def _doc():
    return tomllib.loads((EX / "rotor_rub_runup.toml").read_text())


def _write(tmp_path, doc):
    import tomli_w

    p = tmp_path / "rub.toml"
    p.write_bytes(tomli_w.dumps(doc).encode())
    return p


def _edit(doc, path, value):
    *head, last = path
    t = doc
    for k in head:
        t = t[k]
    if value is None:
        t.pop(last)
    else:
        t[last] = value


@pytest.mark.parametrize("path, value, words", [
    (("rub", 0, "stiffness"), None, "stiffness"),                      # event needs a stiffness
    (("run_up", "method"), "moreau", "no stiffness"),                   # moreau refuses one
    (("rub", 0, "x"), 0.33, "node"),                                    # not a node
    (("rub", 0, "clearance"), -1e-6, "clearance"),
    (("rub", 0, "centre"), [1e-4, 0.0], "centre"),                      # offset beyond the clearance
    (("rub", 0, "colour"), "red", "colour"),                            # unknown key
    (("run_up", "duration"), 0.0, "duration"),
    (("run_up", "speed_end_rpm"), None, "speed_end"),
    (("run_up", "modes"), 1000, "modes"),
    (("run_up",), None, "run_up"),
    (("run_up", "duration"), 1e6, "DRIVEFEM_BUDGET"),                   # refused before it runs
])
def test_bad_run_up_input_is_a_clear_error(tmp_path, capsys, path, value, words):
    doc = _doc()
    _edit(doc, path, value)
    assert main(["simulate", str(_write(tmp_path, doc))]) == 2
    err = capsys.readouterr().err
    assert words in err and "Traceback" not in err


def test_rigid_start_beyond_the_clearance_is_refused(tmp_path, capsys):
    doc = _doc()
    doc["run_up"] |= {"method": "moreau", "speed_start_rpm": 839, "speed_end_rpm": 900, "duration": 0.1}
    doc["rub"][0].pop("stiffness")
    doc["rub"][0].pop("damping")
    assert main(["simulate", str(_write(tmp_path, doc))]) == 2
    assert "start = 'rest'" in capsys.readouterr().err


@pytest.mark.parametrize("method", ["event", "moreau"])
def test_two_rubs_at_once(method):
    """Two rings (one per disc of the Friswell rotor) touched in the same revolutions near the first
    critical speed: both see contact, the balance closes (compliant: at the integration tolerance;
    Moreau-Jean: the identity), and simultaneous rigid contacts are solved by the block Gauss-Seidel
    without a non-convergence warning."""
    L = 1.5
    rotor = Rotor([ShaftSegment(L, 12, 0.05, STEEL)],
                  discs=[Disc.from_geometry(0.5, 0.07, 0.28, 0.05, 7810.0), Disc.from_geometry(1.0, 0.07, 0.35, 0.05, 7810.0)],
                  bearings=[Bearing(0.0, kyy=1e6, kzz=1e6, cyy=3e3, czz=3e3), Bearing(L, kyy=1e6, kzz=1e6, cyy=3e3, czz=3e3)])
    kw = dict(stiffness=5e6, damping=100.0) if method == "event" else dict(restitution=0.3)
    rubs = [Rub(0.5, 40e-6, friction=0.05, **kw), Rub(1.0, 40e-6, friction=0.05, **kw)]
    res = run_up(rotor, RunUp(87.0, 87.0, 0.6, method=method, modes=8, start="rest"), [Unbalance(1.0, 1e-3)], rubs)
    assert res.stopped is None
    assert all(r.in_contact.any() for r in res.rubs)
    assert (res.rubs[0].in_contact & res.rubs[1].in_contact).any()        # measured: 27 % / 9 % of the samples
    assert res.energy_error < (1e-6 if method == "event" else 1e-10)
    assert not any("Gauss-Seidel" in w for w in res.warnings)


def test_first_contact_is_zero_when_the_run_starts_in_contact():
    """start = 'steady' with the linear orbit already beyond an offset ring: in contact at t = 0, then
    separations and new contacts every revolution; first_contact is t = 0, not the first later event."""
    rotor = Rotor([ShaftSegment(0.8, 4, 0.03, MASSLESS)], discs=[Disc(0.4, 10.0)],
                  supports=[Support(0.0), Support(0.8)], bearings=[Bearing(0.4, cyy=300.0, czz=300.0)])
    res = run_up(rotor, RunUp(150.0, 150.0, 0.3, method="event", modes=2), [Unbalance(0.4, 1.5e-3)],
                 [Rub(0.4, 1e-4, stiffness=2e6, centre=(-6e-5, 0.0))], probes=[0.4])
    rub = res.rubs[0]
    assert rub.in_contact[0]
    assert any(e["kind"] == "contact" for e in res.events)          # later contacts exist
    assert rub.first_contact["t"] == 0.0 and rub.first_contact["speed_rad_s"] == 150.0
