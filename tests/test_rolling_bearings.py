"""Rolling-element bearings and the squeeze-film damper example: Hertz contact, the static deflection
under load with clearance, the linearised stiffness, the examples through the CLI, and bad input."""
import json
import math
from pathlib import Path

import numpy as np
import pytest

from discrete.errors import ModelError
from fem.app.cli import main
from fem.rotor.bearings.hertz import ball_contacts, effective_modulus, roller_constant
from fem.rotor.bearings.rolling import RollingBearing

EX = Path(__file__).resolve().parent.parent / "examples"


def _ball(**kw):
    args = dict(x=0.0, element="ball", elements=9, element_diameter=12.7e-3, pitch_diameter=65e-3, clearance=10e-6,
                load=2000.0)
    return RollingBearing(**(args | kw))


def test_hertz_curvature_difference_and_power_law():
    """The 209-size bearing's curvature difference F(rho) written out by hand (Harris ch. 2: gamma =
    D / d_m, groove radius f D) and the 3/2 power of the load-deflection law."""
    D, dm, f = 12.7e-3, 65e-3, 0.52
    E = effective_modulus(2.079e11, 0.3, 2.079e11, 0.3)
    inner, outer = ball_contacts(D, dm, f, f, 0.0, E)
    g = D / dm
    for c, r2 in ((inner, 2 / D * g / (1 - g)), (outer, -2 / D * g / (1 + g))):
        S = 4 / D + r2 - 1 / (f * D)
        assert c.curvature_sum == pytest.approx(S, rel=1e-14)
        assert c.curvature_difference == pytest.approx((r2 + 1 / (f * D)) / S, rel=1e-14)
    assert inner.curvature_difference == pytest.approx(0.93996, abs=1e-5)
    assert inner.deflection(2000.0) / inner.deflection(1000.0) == pytest.approx(2 ** (2 / 3), rel=1e-14)


def test_palmgren_line_contact():
    """delta = 3.84e-5 Q^0.9 / l^0.8 (mm, N) for a 10 mm roller at 1000 N."""
    K = roller_constant(10e-3)
    delta_mm = 3.84e-5 * 1000.0 ** 0.9 / 10.0 ** 0.8
    assert K * (delta_mm * 1e-3) ** (10 / 9) == pytest.approx(1000.0, rel=1e-12)


def test_static_deflection_carries_the_load_at_every_cage_position():
    b = _ball()
    for cage in np.linspace(0.0, 2 * math.pi / 9, 5):
        r = b.deflection(cage)
        assert np.allclose(-b.elastic_force(*r, cage), b.static_load(), rtol=1e-9, atol=1e-9)
        assert r[1] < -b.clearance                     # down through the clearance
    # unloaded with clearance: centred and no stiffness; preloaded: stiff in every direction
    assert np.allclose(_ball(load=0.0).deflection(), 0.0)
    pre = _ball(load=0.0, clearance=-2e-6).linearised_stiffness()
    assert pre[0, 0] > 0 and pre[1, 1] == pytest.approx(pre[0, 0], rel=1e-9)


def test_stiffness_grows_with_load_and_clearance_makes_it_anisotropic():
    k1, k2 = _ball(load=500.0).linearised_stiffness(), _ball(load=4000.0).linearised_stiffness()
    assert k2[1, 1] > k1[1, 1] > 0
    assert k1[1, 1] > 1.5 * k1[0, 0]                     # along the load stiffer than across (few balls loaded)
    with pytest.raises(ModelError) as e:
        _ball(load=0.0).table()
    assert e.value.key == "load"


@pytest.mark.parametrize("kw, key", [({"elements": 2}, "elements"), ({"element": "needle"}, "element"),
                                     ({"inner_conformity": 0.5}, "inner_conformity"),
                                     ({"element_diameter": 0.1}, "element_diameter"),
                                     ({"element": "roller"}, "roller_length"), ({"damping": -1.0}, "damping"),
                                     ({"speeds": [1.0, 2.0]}, "speeds"), ({"kzz": 1e6}, "kzz")])
def test_rolling_bearing_rejects_bad_values(kw, key):
    with pytest.raises(ModelError) as e:
        _ball(**kw).check("[[rotor.rolling_bearing]] #1")
    assert e.value.key == key


def test_ball_bearing_example_modal(tmp_path):
    out = tmp_path / "m.json"
    assert main(["modal", str(EX / "rotor_ball_bearings.toml"), "--json", str(out)]) == 0
    d = json.loads(out.read_text())
    assert d["omega_rad_s"][0] == pytest.approx(619.1, rel=1e-3)        # measured when the example was written


def test_squeeze_film_example_damping(tmp_path):
    """The damper's linear damping at the centre is pi mu R L^3 / (2 c^3) (pi film)."""
    from fem.study import Study

    rs = Study.load(EX / "rotor_squeeze_film_damper.toml").rotor
    d = rs.rotor.bearings[1]
    assert d.table()["cyy"][0] == pytest.approx(math.pi * 0.01 * 0.04 * 0.015 ** 3 / (2 * 1e-4 ** 3), rel=1e-8)
    assert main(["modal", str(EX / "rotor_squeeze_film_damper.toml"), "--json", str(tmp_path / "m.json")]) == 0


@pytest.mark.slow
def test_ball_bearing_example_runup(tmp_path):
    """The journals fall into the clearance and the balls carry the weight and the unbalance."""
    out = tmp_path / "sim.json"
    assert main(["simulate", str(EX / "rotor_ball_bearings.toml"), "--json", str(out), "--png", str(tmp_path)]) == 0
    d = json.loads(out.read_text())
    ecc = [b["max_eccentricity"] for b in d["bearings"]]
    assert all(1.0 < e < 2.0 for e in ecc)                # beyond the 10 um play, by the Hertzian deflection
    assert d["energy"]["relative_error"] < 1e-5
    assert (tmp_path / "run_up_orbits.png").exists()
