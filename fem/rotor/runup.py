"""Run-up (or coast-down, or constant speed) of a rotor with rotor-stator rub and bearing clearances.

:func:`run_up` reduces the rotor (:mod:`fem.rotor.reduced`: modes at rest plus static attachment
shapes at every rub), starts from rest or from the linear synchronous steady state at the first
speed, and integrates along the speed ramp with compliant contacts located event by event or
rigid contacts by Moreau-Jean (:mod:`fem.rotor.transient`).  The result holds the orbits at the
probes, the rubs' normal forces, slip velocities and regimes (no rub, partial rub: contact over
part of a revolution, full annular rub: contact over whole revolutions), the events, the energy
balance and the reduction's restitution.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from discrete import checks
from discrete.errors import ModelError
from discrete.nonsmooth.elements.radial import RadialClearance

from . import nonlinear_bearings as nlb
from .assembly import RotorSystem
from .modal import as_system
from .reduced import ReducedRotor, reduce_rotor
from .transient import (WORKS, SpeedRamp, Trajectory, UnbalanceLoad, check_rigid, integrate_compliant,
                        integrate_moreau)

METHODS = ("event", "moreau")
INTEGRATORS = ("auto", "DOP853", "LSODA")
STARTS = ("steady", "rest")


@dataclass
class Rub:
    """A stator ring of radial ``clearance`` (m) around the shaft at ``x`` (a node): rotor-stator rub
    (seal, casing) or a bearing clearance (the bearing's stiffness as ``stiffness``, friction 0).

    ``stiffness`` k (N/m) and ``damping`` c_n (N s/m): compliant contact (``method = "event"``);
    ``stiffness`` None: rigid contact with Newton's ``restitution`` (``method = "moreau"``);
    ``friction`` mu (Coulomb); ``radius`` R of the shaft at the contact (m; None: half the shaft's
    outer diameter there); ``centre`` (c_y, c_z): offset of the stator centre (m)."""

    x: float
    clearance: float
    stiffness: float | None = None
    damping: float = 0.0
    restitution: float = 0.5
    friction: float = 0.0
    radius: float | None = None
    centre: tuple = (0.0, 0.0)
    name: str = ""


@dataclass
class RunUp:
    """A speed ramp from ``speed_start`` to ``speed_end`` (rad/s, >= 0; equal: constant speed) over
    ``duration`` (s); ``method`` "event" (compliant rubs) or "moreau" (rigid rubs); ``modes``
    retained modes at rest (plus 2 attachment shapes per rub); ``time_step`` of Moreau-Jean (None:
    a 40th of the shortest retained period); ``output_step`` (None: a 64th of the shortest
    revolution, at most 20 000 samples); ``rtol`` of the event-located integrator; ``start``
    "steady" (the linear synchronous response at ``speed_start``, no contact force; on bearings
    computed from their geometry about their static state, with their laws linearised there) or "rest";
    ``max_events``: a chattering contact stops the run beyond this many events; ``integrator`` of
    ``method = "event"``: "DOP853" (explicit), "LSODA" (stiff phases by BDF), "auto" (LSODA when
    bearings computed from their geometry act, whose films are stiff on light journals; else DOP853)."""

    speed_start: float
    speed_end: float
    duration: float
    method: str = "event"
    modes: int = 12
    time_step: float | None = None
    output_step: float | None = None
    rtol: float = 1e-8
    start: str = "steady"
    max_events: int = 100_000
    integrator: str = "auto"

    def check(self) -> None:
        where = "[run_up]"
        for key in ("speed_start", "speed_end"):
            checks.non_negative(where, key, getattr(self, key), "a speed in rad/s")
        checks.positive(where, "duration", self.duration, "s")
        checks.choice(where, "method", self.method, METHODS)
        checks.choice(where, "start", self.start, STARTS)
        for key in ("time_step", "output_step"):
            checks.optional(checks.bounded, where, key, getattr(self, key), (">", 0.0), ("<=", self.duration),
                            "s: a step no longer than the duration")
        checks.bounded(where, "rtol", self.rtol, (">=", 1e-13), ("<=", 1e-3), "relative tolerance")
        checks.integer(where, "max_events", self.max_events, 1)
        checks.choice(where, "integrator", self.integrator, INTEGRATORS)


@dataclass
class RubHistory:
    """One rub over the run: ``normal_force`` N (N; Moreau: impulse / step), ``slip`` velocity
    (m/s), ``in_contact``, ``radius`` |r - c| (m) and ``regime`` per sample ("none", "partial",
    "full": the contact share over the last revolution of the shaft is 0, between, or 1), the
    first contact, the number of contact phases and the full annular rub intervals."""

    name: str
    x: float
    clearance: float
    centre: tuple
    normal_force: np.ndarray
    slip: np.ndarray
    in_contact: np.ndarray
    radius: np.ndarray
    regime: np.ndarray
    first_contact: dict | None
    contact_phases: int
    full_annular: list
    max_penetration: float

    def to_dict(self) -> dict:
        return {"name": self.name, "x": self.x, "clearance": self.clearance, "centre": list(self.centre),
                "max_normal_force": float(self.normal_force.max(initial=0.0)),
                "max_radius": float(self.radius.max(initial=0.0)), "first_contact": self.first_contact,
                "contact_phases": self.contact_phases, "full_annular_rub": self.full_annular,
                "contact_share": float(self.in_contact.mean()) if self.in_contact.size else 0.0,
                "max_penetration": self.max_penetration}


@dataclass
class RunUpResult:
    """A run-up: samples ``t`` (s) and ``speed`` (rad/s), orbits ``orbit_y``/``orbit_z`` (m) at
    ``probe_x``, the ``rubs``, the ``events`` (contact, separation, stick, slip, ...), the energy
    balance (``works``, ``energy_start``/``energy_end``, ``energy_error`` relative to the largest
    term), the reduction report, ``stopped`` (None: reached the end; else why not); ``bearings``: the
    histories of the bearings computed from their geometry (their nonlinear laws acted in the run)."""

    t: np.ndarray
    speed: np.ndarray
    probe_x: np.ndarray
    orbit_y: np.ndarray
    orbit_z: np.ndarray
    rubs: list
    events: list
    works: dict
    energy_start: float
    energy_end: float
    energy_error: float
    reduction: dict
    method: str
    stopped: str | None
    steps: int
    wall_time: float
    warnings: list = field(default_factory=list)
    bearings: list = field(default_factory=list)
    integrator: str = "DOP853"
    probe_names: list = field(default_factory=list)     # the named thing at each probe ("" if none)
    eta: np.ndarray | None = field(default=None, repr=False)       # (n_t, n_basis) the reduced coordinates
    eta_dot: np.ndarray | None = field(default=None, repr=False)   # (n_t, n_basis) their rates
    basis: np.ndarray | None = field(default=None, repr=False)     # (n_dofs, n_basis): q = basis @ eta

    def probe_label(self, k: int) -> str:
        """The name of probe k in the outputs: the disc/bearing/coupling/rub there, else x=<x>."""
        n = self.probe_names[k] if k < len(self.probe_names) else ""
        return n or f"x={self.probe_x[k]:g}"

    def to_dict(self, samples: bool = False) -> dict:
        out = {"method": self.method, "t_end": float(self.t[-1]) if self.t.size else 0.0,
               "speed_start_rad_s": float(self.speed[0]) if self.speed.size else 0.0,
               "speed_end_rad_s": float(self.speed[-1]) if self.speed.size else 0.0,
               "steps": self.steps, "wall_time_s": self.wall_time, "stopped": self.stopped,
               "rubs": [r.to_dict() for r in self.rubs], "events": self.events,
               "energy": {"start": self.energy_start, "end": self.energy_end, "works": self.works,
                          "relative_error": self.energy_error},
               "peak_amplitude": {(self.probe_names[k] if k < len(self.probe_names) and self.probe_names[k]
                                   else f"{x:g}"): float(np.hypot(self.orbit_y[:, k], self.orbit_z[:, k]).max(initial=0.0))
                                  for k, x in enumerate(self.probe_x)},
               "reduction": self.reduction, "warnings": list(self.warnings)}
        if self.bearings:
            out["bearings"] = [b.to_dict() for b in self.bearings]
        if self.method == "event" and (self.bearings or self.integrator != "DOP853"):
            out["integrator"] = self.integrator
        if samples:
            out["samples"] = {"t": self.t.tolist(), "speed_rad_s": self.speed.tolist(),
                              "orbit_y": self.orbit_y.T.tolist(), "orbit_z": self.orbit_z.T.tolist(),
                              "probes": [self.probe_label(k) for k in range(self.probe_x.size)]}
        return out


def _laws(rs: RotorSystem, red: ReducedRotor, rubs) -> list[RadialClearance]:
    laws = []
    for i, r in enumerate(rubs, 1):
        where = f"[[rub]] #{i}"
        node = rs.node(r.x, where)
        iv, iw = int(rs.node_dofs["v"][node]), int(rs.node_dofs["w"][node])
        radius = r.radius
        if radius is None:
            radius = 0.5 * _outer_diameter(rs, r.x)
        laws.append(RadialClearance(name=r.name or f"rub {i} at x = {r.x:g} m", g_y=red.T[iv], g_z=red.T[iw],
                                    clearance=r.clearance, stiffness=r.stiffness, damping=r.damping,
                                    restitution=r.restitution, friction=r.friction, radius=radius,
                                    centre=tuple(r.centre)))
    return laws


def _outer_diameter(rs: RotorSystem, x: float) -> float:
    """The largest outer diameter of the shaft at x (a node between two segments: the larger)."""
    x0, best = 0.0, 0.0
    for s in rs.rotor.segments:
        x1 = x0 + s.length
        if x0 - 1e-12 <= x <= x1 + 1e-12:
            u = min(max((x - x0) / s.length, 0.0), 1.0)
            best = max(best, s.outer_diameter(u))
        x0 = x1
    return best


def _regime(t: np.ndarray, speed: np.ndarray, contact: np.ndarray) -> np.ndarray:
    """Per sample: the contact share over the last revolution of the shaft -> none/partial/full."""
    out = np.full(t.size, "none", dtype=object)
    if not t.size:
        return out
    c = np.concatenate([[0], np.cumsum(contact.astype(int))])
    k = np.arange(t.size)
    T_rev = 2 * math.pi / np.maximum(speed, 1e-12)
    i0 = np.searchsorted(t, t - T_rev)               # first sample of the revolution ending at t[k]
    m = c[k + 1] - c[i0]
    full = (m == k + 1 - i0) & (t - t[i0] >= 0.95 * T_rev)
    out[m > 0] = "partial"
    out[(m > 0) & full] = "full"
    return out


def _intervals(t: np.ndarray, flags: np.ndarray) -> list:
    out, start = [], None
    for k, f in enumerate(flags):
        if f and start is None:
            start = t[k]
        if not f and start is not None:
            out.append([float(start), float(t[k - 1])])
            start = None
    if start is not None:
        out.append([float(start), float(t[-1])])
    return out


def run_up(rotor, run: RunUp, unbalances=(), rubs=(), probes=None, progress=None, check_steps=None) -> RunUpResult:
    """Integrate ``rotor`` (a :class:`Rotor` or :class:`RotorSystem`) along the speed ramp of
    ``run`` with the ``unbalances`` (:class:`fem.rotor.Unbalance`) and the ``rubs``; ``probes``:
    positions of the orbit outputs (default: every rub, disc and bearing); ``progress(fraction)``;
    ``check_steps(estimate, note)``: a budget that may refuse the run before it starts."""
    wall = time.perf_counter()
    rs = as_system(rotor)
    run.check()
    rubs = list(rubs)
    ramp = SpeedRamp(float(run.speed_start), float(run.speed_end), float(run.duration))
    nonlinear = nlb.nonlinear_bearings(rs)
    dyn = nlb.dynamic_system(rs) if nonlinear else rs
    if dyn.tables:                                          # bearing tables must cover the ramp
        dyn.coefficients([ramp.start, ramp.end])
    contact_dofs = [(rs.dof(r.x, "v", f"[[rub]] #{i}"), rs.dof(r.x, "w", f"[[rub]] #{i}")) for i, r in enumerate(rubs, 1)]
    if nonlinear:
        lo = max((t.grid[0] for t in rs.tables), default=ramp.start)
        hi = min((t.grid[-1] for t in rs.tables), default=ramp.start)
        red = reduce_rotor(dyn, np.array(contact_dofs + nlb.bearing_dofs(rs, nonlinear), dtype=int).reshape(-1, 2),
                           run.modes, reference_speed=ramp.start, basis_system=rs, basis_speed=min(max(ramp.start, lo), hi))
    else:
        red = reduce_rotor(rs, np.array(contact_dofs, dtype=int).reshape(-1, 2), run.modes, reference_speed=ramp.start)
    laws = _laws(rs, red, rubs)
    smooth = nlb.elements(rs, red.T, nonlinear)
    f_static = nlb.static_load(rs, nonlinear) if nonlinear else None
    static = None if f_static is None else red.T.T @ f_static
    check_rigid(laws, run.method)
    # unbalance forces in reduced coordinates
    A_y = np.zeros(red.n, complex)
    A_z = np.zeros(red.n, complex)
    for i, u in enumerate(unbalances, 1):
        node = rs.node(u.x, f"[[unbalance]] #{i}")
        ph = np.exp(1j * u.phase)
        A_y += u.magnitude * ph * red.T[rs.node_dofs["v"][node]]
        A_z += u.magnitude * ph * red.T[rs.node_dofs["w"][node]]
    load = UnbalanceLoad(A_y, A_z, ramp)
    eta0 = np.zeros(red.n)
    v0 = np.zeros(red.n)
    if run.start == "steady" and ramp.start > 0:
        K, C = red.matrices(ramp.start)
        eta_s = np.zeros(red.n)
        if smooth:                          # the static state on the nonlinear bearings, and their linearisation
            rhs = np.zeros(red.n) if static is None else static
            eta_s = nlb.equilibrium(K, smooth, rhs, ramp.start, np.linalg.solve(red.basis_stiffness, rhs))
            Kb, Cb = nlb.linearised(smooth, eta_s, np.zeros(red.n), ramp.start)
            K, C = K + Kb, C + Cb
        Y = np.linalg.solve(K - ramp.start ** 2 * np.eye(red.n) + 1j * ramp.start * C, load.steady_amplitude(ramp.start))
        eta0, v0 = eta_s + Y.real, -ramp.start * Y.imag
        for c in laws:
            rho = float(c.relative(c.g_y @ eta0, c.g_z @ eta0)[2])
            if c.rigid and rho > c.clearance:
                raise ModelError("[run_up]", "start", run.start, f"a start inside the clearances: the linear steady "
                                 f"orbit at speed_start = {ramp.start:g} rad/s reaches {rho:.4g} m at {c.name!r}, beyond "
                                 f"its clearance {c.clearance:g} m (a rigid contact cannot start penetrated): "
                                 "start = 'rest' or a lower speed_start")
    w_top = max(ramp.start, ramp.end, 1e-12)
    out_step = run.output_step or min(2 * math.pi / w_top / 64, ramp.duration / 200)
    n_out = int(min(ramp.duration / out_step, 20_000)) + 1
    t_out = np.linspace(0.0, ramp.duration, n_out)
    warnings = list(red.warnings)
    if red.omega.max() < 2 * w_top:
        warnings.append(f"the basis' highest frequency {red.omega.max():.4g} rad/s is below twice the top speed "
                        f"{w_top:.4g} rad/s: retain more modes ([run_up] modes)")
    if run.method == "event":
        # the stiffest motion: the basis' top frequency with every contact's stiffness on its shape
        w_c = math.sqrt(red.omega.max() ** 2 + sum((c.stiffness or 0.0) * (c.g_y @ c.g_y + c.g_z @ c.g_z) for c in laws))
        estimate, note = ramp.duration * max(w_c, w_top) * 16 / (2 * math.pi), f"steps (16 per period of {w_c:.3g} rad/s)"
    else:
        h = run.time_step or 2 * math.pi / max(red.omega.max(), w_top) / 40
        estimate, note = ramp.duration / h, f"Moreau-Jean steps of {h:.3g} s"
    if check_steps is not None:
        check_steps(estimate, note)
    integrator = run.integrator if run.integrator != "auto" else ("LSODA" if smooth else "DOP853")
    if run.method == "event":
        traj: Trajectory = integrate_compliant(red, ramp, load, laws, eta0, v0, t_out, rtol=run.rtol,
                                               max_events=run.max_events, progress=progress, smooth=smooth,
                                               static=static, integrator=integrator)
    else:
        traj = integrate_moreau(red, ramp, load, laws, eta0, v0, t_out, h, progress=progress, smooth=smooth,
                                static=static)
    # outputs
    if probes is None:
        xs = sorted({float(r.x) for r in rubs} | {float(d.x) for d in rs.rotor.discs}
                    | {float(b.x) for b in rs.rotor.bearings})
    else:
        xs = [float(x) for x in probes]
    iv = np.array([rs.dof(x, "v", "probe") for x in xs], dtype=int)
    iw = np.array([rs.dof(x, "w", "probe") for x in xs], dtype=int)
    orbit_y, orbit_z = traj.eta @ red.T[iv].T, traj.eta @ red.T[iw].T
    speed = ramp.speed(traj.t)
    from .response import place_name

    rub_at = {float(r.x): (r.name or "") for r in rubs}
    names = [place_name(rs.rotor, x) or rub_at.get(float(x), "") for x in xs]
    hist = []
    for j, (r, c) in enumerate(zip(rubs, laws)):
        y, z = traj.eta @ c.g_y, traj.eta @ c.g_z
        rho = c.relative(y, z)[2]
        if traj.in_contact[:1, j].any():            # in contact from the start: that is the first contact
            first = {"t": 0.0, "kind": "contact", "rub": c.name, "speed_rad_s": float(ramp.start)}
        else:
            first = next((e for e in traj.events if e["rub"] == c.name and e["kind"] == "contact"), None)
        regime = _regime(traj.t, speed, traj.in_contact[:, j])
        hist.append(RubHistory(name=c.name, x=float(r.x), clearance=c.clearance, centre=c.centre, normal_force=traj.normal_force[:, j],
                               slip=traj.slip[:, j], in_contact=traj.in_contact[:, j], radius=rho, regime=regime,
                               first_contact=first,
                               contact_phases=sum(1 for e in traj.events if e["rub"] == c.name and e["kind"] == "contact")
                               + int(bool(traj.in_contact[:1, j].any())),
                               full_annular=_intervals(traj.t, regime == "full"),
                               max_penetration=float(traj.max_penetration[j])))
    lateral = [w for k, w in traj.works.items() if k != "spin_friction"]
    scale = max([abs(traj.energy_start), abs(traj.energy_end)] + [abs(w) for w in lateral] + [1e-300])
    err = abs(traj.energy_end - traj.energy_start - sum(lateral)) / scale
    if abs(traj.works.get("projection", 0.0)) > 1e-2 * scale:
        warnings.append(f"Moreau-Jean's position projection changed the strain energy by "
                        f"{traj.works['projection']:.3g} J ({100 * abs(traj.works['projection']) / scale:.2g} % of the "
                        "largest energy term): a smaller time_step")
    warnings += traj.warnings
    if traj.stopped:
        warnings.append(traj.stopped)
    reduction = red.report()
    reduction["frequency_check"] = red.frequency_check(w_top, min(4, red.n_modes))
    return RunUpResult(t=traj.t, speed=speed, probe_x=np.array(xs), orbit_y=orbit_y, orbit_z=orbit_z, rubs=hist,
                       probe_names=names, eta=traj.eta, eta_dot=traj.eta_dot, basis=red.T,
                       events=traj.events, works=dict(traj.works), energy_start=traj.energy_start,
                       energy_end=traj.energy_end, energy_error=float(err), reduction=reduction, method=run.method,
                       stopped=traj.stopped, steps=traj.steps, wall_time=time.perf_counter() - wall, warnings=warnings,
                       bearings=nlb.histories(rs, nonlinear, smooth, traj.eta, traj.eta_dot, speed,
                                              ramp.angle(traj.t)) if nonlinear else [], integrator=integrator)


__all__ = ["Rub", "RunUp", "RunUpResult", "RubHistory", "run_up", "METHODS", "WORKS"]
