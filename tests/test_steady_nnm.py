"""Backbone curves by the extended periodic motion concept (discrete/steady/nnm.py)."""
import math

import numpy as np
from scipy.special import ellipk

from discrete.steady import HBModel
from discrete.steady.nnm import FreeSystem, backbone
from fem.study import Study
from validation.examples import example_doc


def test_duffing_backbone_is_the_elliptic_law_and_xi_cancels_c():
    sm = Study.parse(example_doc("steady_duffing.toml")).steady_model()
    H = 7
    X0 = np.zeros(2 * H + 1)
    X0[1] = 1.5
    bb = backbone(sm.system, H, [1.5, 1.0, 0.5], X0, 1.4)
    hb = HBModel(FreeSystem(sm.system), harmonics=H)
    assert bb.completed and np.allclose(bb.xi, 0.1, rtol=1e-12, atol=0)
    for w, X in zip(bb.omega, bb.states):
        _, q, _ = hb.evaluate(X, w, points=4096)
        A = float(np.max(q[0]))
        p = 0.5 * A * A / (2 * (1 + 0.5 * A * A))
        exact = math.pi * math.sqrt(1 + 0.5 * A * A) / (2 * ellipk(p))
        assert abs(w / exact - 1) < 5e-7


def test_backbone_in_the_forced_json_and_plot(tmp_path):
    from fem.output.figures import plot_afc

    d = example_doc("steady_coulomb.toml")
    d["steady"]["backbone"] = True
    r = Study.parse(d).forced()
    bb = r.extra["backbone"]
    assert bb["completed"] and bb["n_points"] == 40
    # the EPMC of a Coulomb oscillator: omega < 1, damping ratio falling with the amplitude (~ 4F/(pi A)/2)
    D = np.array(bb["damping_ratio"])
    assert np.all(np.array(bb["omega_rad_s"]) < 1.0) and np.all(np.diff(D) > 0)
    A0 = bb["first_harmonic_amplitude"][0]
    assert abs(D[0] / (4 * 0.3 / (math.pi * A0) / 2) - 1) < 0.02
    plot_afc(r, tmp_path / "afc.png")
    assert (tmp_path / "afc.png").stat().st_size > 10_000
