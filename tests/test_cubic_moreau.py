"""Cubic springs in Moreau-Jean time stepping (textbook (8.20)) and the HB start from a time run."""
import numpy as np
import pytest

from discrete.errors import ModelError
from discrete.steady.estimates import subharmonic_third
from fem.modelfile.source import read_toml
from fem.study import Study
from validation.analytic.steady_refs import duffing_backbone_exact
from validation.examples import EXAMPLES


def _free_duffing(steps_per_period: int, periods: int = 10):
    """q'' + q + 0.5 q^3 = 0 from q = 1 at rest by Moreau-Jean; (period, energy error, T exact)."""
    T = 2 * np.pi / float(duffing_backbone_exact(1.0, 0.5, 1.0))
    d = {"title": "free duffing", "body": [{"name": "m", "inertia": 1.0, "x0": 1.0}],
         "spring": [{"between": ["ground", "m"], "k": 1.0}],
         "cubic_spring": [{"between": ["ground", "m"], "k3": 0.5}],
         "simulation": {"t_end": periods * T, "method": "moreau", "dt": T / steps_per_period,
                        "samples": periods * steps_per_period}}
    r = Study.parse(d).simulate()
    x, t = r.x[0], r.t
    i = np.flatnonzero((x[:-1] > 0) & (x[1:] <= 0))
    tc = t[i] + (t[i + 1] - t[i]) * x[i] / (x[i] - x[i + 1])
    return float(np.mean(np.diff(tc))), float(r.energy_error), T


def test_cubic_spring_moreau_is_second_order_and_conserves_energy():
    """The period against the exact elliptic value: error falls 4x per halved step (midpoint rule,
    theta = 1/2); the discrete-gradient impulse keeps the energy to the solve tolerance."""
    errs = []
    for n in (50, 100):
        Tm, e, T = _free_duffing(n)
        errs.append(abs(Tm / T - 1))
        assert abs(e) < 1e-9
    assert errs[1] < 2e-3
    assert 3.5 < errs[0] / errs[1] < 4.5


def test_subharmonic_estimate_refuses_points_off_the_backbone():
    with pytest.raises(ModelError, match="omega"):
        subharmonic_third(1.0, 0.5, 0.9)


def test_steady_time_start_is_an_hb_option():
    d = read_toml(EXAMPLES / "steady_subharmonic.toml")
    d["steady"]["method"] = "shooting"
    with pytest.raises(ModelError, match="start"):
        Study.parse(d)
