"""The named outputs along an amplitude-frequency curve (``drivefem forced`` of a ``[steady]`` file): at
every point of the curve the periodic orbit over one (sub)harmonic period -- the harmonic-balance
coefficients evaluated in time, or one period map of shooting integrated by the event solver -- and
of every output its amplitude (half the peak-to-peak), peak |y| and mean over the period."""
from __future__ import annotations

import numpy as np

from discrete.loads.channels import history_quantities, load_factor

from .drive import selected


def curve_outputs(study, sm, res, points: int = 512) -> dict:
    """{output name: description, ``amplitude``, ``peak``, ``mean``, ``dynamic_load_factor`` (forces: peak
    over |mean|), one value per point of the curve ``res`` (:class:`discrete.steady.AFCResult`) of the
    steady model ``sm``}.  The orbits of HB share one sampling: their channels are evaluated in one call
    per chunk of :data:`CHUNK` orbits and reduced over each orbit at once
    (:func:`discrete.loads.channels.history_quantities`); shooting orbits one by one."""
    loads = study.time_loads
    lm = selected(study, loads)
    cols = {c.name: {"amplitude": [], "peak": [], "mean": [], "dynamic_load_factor": []} for c in lm.channels}
    orbits = _hb_orbits(sm, res, points) if sm.cfg.method == "hb" else _shooting_orbits(sm, res)
    groups = _chunks(orbits, CHUNK if sm.cfg.method == "hb" else 1)
    for group in groups if lm.channels else ():
        T = np.stack([np.asarray(o[0], float) for o in group])                  # (orbits, samples)
        Y = lm.values(*(_columns(group, j, T.shape[1]) for j in range(1, 6)), T.ravel())
        q = history_quantities(T, np.asarray(np.real_if_close(Y), float).reshape(len(lm.channels), *T.shape))
        for k, c in enumerate(lm.channels):
            col = cols[c.name]
            col["amplitude"] += (0.5 * (q["max"][k] - q["min"][k])).tolist()
            col["peak"] += q["peak"][k].tolist()
            col["mean"] += q["mean"][k].tolist()
            col["dynamic_load_factor"] += [load_factor(p, m) if c.is_force else None
                                           for p, m in zip(q["peak"][k].tolist(), q["mean"][k].tolist())]
    out = {}
    for c in lm.channels:
        amp = cols[c.name]["amplitude"]
        k = int(np.argmax(amp)) if amp else None
        out[c.name] = {**c.describe(), **cols[c.name], "max_amplitude": None if k is None else amp[k],
                       "at_omega_rad_s": None if k is None else float(res.omega[k])}
    return out


#: HB orbits evaluated together (they share one sampling): the memory of a chunk is CHUNK x (states +
#: loads) x samples, whatever the number of points of the curve
CHUNK = 64


def _chunks(orbits, size: int):
    """Lists of up to ``size`` consecutive orbits with one sample count (a new list where it changes)."""
    chunk = []
    for orbit in orbits:
        if chunk and (len(chunk) == size or np.size(orbit[0]) != np.size(chunk[0][0])):
            yield chunk
            chunk = []
        chunk.append(orbit)
    if chunk:
        yield chunk


def _columns(group, j: int, samples: int):
    """Part j of every orbit of ``group`` side by side (rows: coordinates, columns: the orbits' samples in
    turn), or None where the orbits have none."""
    if any(o[j] is None for o in group):
        return None
    return np.concatenate([np.asarray(o[j]).reshape(-1, samples) for o in group], axis=1)


def _hb_orbits(sm, res, points: int):
    from discrete.steady.hb import HBModel

    cfg = sm.cfg
    hb = HBModel(sm.system, harmonics=cfg.harmonics, nu=cfg.subharmonic, samples=cfg.samples)
    ws = [float(w) for w in res.omega]
    problems = sm.spec.problems(ws) if hasattr(sm.spec, "problems") else map(sm.factory, ws)
    for X, w, p in zip(res.states, res.omega, problems):
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
