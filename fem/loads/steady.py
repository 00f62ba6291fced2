"""The named outputs along an amplitude-frequency curve (``drivefem forced`` of a ``[steady]`` file): at
every point of the curve the periodic orbit over one (sub)harmonic period -- the harmonic-balance
coefficients evaluated in time, or one period map of shooting integrated by the event solver -- and
of every output its amplitude (half the peak-to-peak), peak |y| and mean over the period."""
from __future__ import annotations

import numpy as np

from .analyses import time_outputs
from .drive import selected


def curve_outputs(study, sm, res, points: int = 512) -> dict:
    """{output name: description, ``amplitude``, ``peak``, ``mean``, ``dynamic_load_factor`` (forces: peak
    over |mean|), one value per point of the curve ``res`` (:class:`discrete.steady.AFCResult`) of the
    steady model ``sm``}."""
    loads = study.time_loads
    lm = selected(study, loads)
    cols = {c.name: {"amplitude": [], "peak": [], "mean": [], "dynamic_load_factor": []} for c in lm.channels}
    orbits = _hb_orbits(sm, res, points) if sm.cfg.method == "hb" else _shooting_orbits(sm, res)
    for t, x, v, a, F, f in orbits:
        out = time_outputs(lm, t, x, v, a, F, f)
        for c in lm.channels:
            s = out.summaries[c.name]
            cols[c.name]["amplitude"].append(0.5 * s["peak_to_peak"])
            cols[c.name]["peak"].append(s["peak"])
            cols[c.name]["mean"].append(s["mean"])
            cols[c.name]["dynamic_load_factor"].append(s.get("dynamic_load_factor"))
    out = {}
    for c in lm.channels:
        amp = cols[c.name]["amplitude"]
        k = int(np.argmax(amp)) if amp else None
        out[c.name] = {**c.describe(), **cols[c.name], "max_amplitude": None if k is None else amp[k],
                       "at_omega_rad_s": None if k is None else float(res.omega[k])}
    return out


def _hb_orbits(sm, res, points: int):
    from discrete.steady.hb import HBModel

    cfg = sm.cfg
    hb = HBModel(sm.system, harmonics=cfg.harmonics, nu=cfg.subharmonic, samples=cfg.samples)
    for X, w in zip(res.states, res.omega):
        p = sm.factory(float(w))
        t, q, v = hb.evaluate(np.asarray(X), float(w), points=max(points, hb.N))
        E = p.basis_many(t)
        x, xd = p.full_state(q, v, E)
        F = sm.system.element_series(t, q, v, float(w))[0] if sm.system.elements else np.zeros((0, t.size))
        a, f = p.recover(t, x, xd, F)
        yield t, x, xd, a, F, f


def _shooting_orbits(sm, res):
    from discrete.steady.shooting import ShootingModel

    cfg = sm.cfg
    sh = ShootingModel(sm.factory, nu=cfg.subharmonic, steps_per_period=cfg.steps_per_period)
    phases = res.extra.get("section_phase_rad", [0.0] * len(res.states))
    for y, w, ph in zip(res.states, res.omega, phases):
        _, r = sh.run(np.asarray(y), float(w), dense=True, phase=float(ph))
        yield r.t, r.x, r.v, r.acceleration, r.element_forces, r.applied
