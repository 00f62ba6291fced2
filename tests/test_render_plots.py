"""Matplotlib figures from result objects (files, no display)."""
from types import SimpleNamespace

import matplotlib.image as mpimg
import numpy as np

from fem import assemble, modal_analysis
from fem.output.figures import extra as px
from validation.builders import uniform


def _ink(path):
    img = mpimg.imread(path)[..., :3]
    return float((img.min(axis=-1) < 0.9).mean())


def test_convergence_and_campbell(tmp_path):
    n = np.array([4, 8, 16, 32])
    p = px.plot_convergence(n, {"mode 1": 1e-2 * (n / 4.0) ** -4, "mode 2": 3e-2 * (n / 4.0) ** -4}, tmp_path / "c.png")
    assert p.is_file() and _ink(p) > 0.01
    # Campbell from modal results of a stiffening parameter (tip mass varied)
    res = []
    masses = np.linspace(0.0, 2.0, 5)
    for m in masses:
        model = uniform("bending", 1.0, 10, d=0.03, supports=[(0.0, "clamped")], points=[{"x": 1.0, "mass": m}])
        res.append(modal_analysis(assemble(model).system, 2))
    p = px.plot_campbell(masses * 1000, res, tmp_path / "campbell.png", xlabel="parameter")
    assert _ink(p) > 0.01


def test_afc_phase_portrait_time_history(tmp_path):
    f = np.linspace(1, 10, 50)
    afc = SimpleNamespace(frequencies_hz=f, amplitude=1 / np.abs(25 - f**2 + 0.5j * f), outputs=["tip"])
    assert _ink(px.plot_amplitude_curve(afc, tmp_path / "afc.png", stable=f < 7)) > 0.005
    t = np.linspace(0, 10, 500)
    ev = [SimpleNamespace(t=ti, state={"disk": {"x": np.sin(ti), "v": np.cos(ti)}}) for ti in (1.0, 4.0)]
    sim = SimpleNamespace(t=t, x=np.array([np.sin(t)]), v=np.array([np.cos(t)]), names=["disk"], events=ev, period=2 * np.pi)
    assert _ink(px.plot_phase_portrait(sim, tmp_path / "pp.png")) > 0.005
    assert _ink(px.plot_time_series(sim, tmp_path / "th.png")) > 0.005
