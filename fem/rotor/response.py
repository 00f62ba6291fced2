"""Unbalance response: amplitude and phase along the shaft, Bode/polar data, orbits, peaks and
API 684-style amplification factors and separation margins.

At the speed Omega the unbalance forces turn with the shaft, so the steady response is
synchronous, q = Re(Q e^{i Omega t}) with

    (K(Omega) - Omega^2 M + i Omega (C(Omega) + Omega G)) Q = Omega^2 F_u,
    F_u[v] = m e e^{i phase},  F_u[w] = -i m e e^{i phase}   (f_y + i f_z = m e Omega^2 e^{i (Omega t + phase)}).

One sparse direct solve per speed, never an inverse: only the independent block of the DOF
graph that the unbalances load is solved (a rotor's lateral DOFs), in the reverse
Cuthill-McKee band order, and all speeds of a chunk are factorised by one LAPACK ``zgbtrf`` call
on the band matrices stacked along the diagonal (:class:`discrete.linalg.banded.BandedLU`).

Peaks of a probe's amplitude are refined by a bounded scalar maximisation and the half-power
speeds N1 < Nc < N2 (amplitude peak / sqrt 2) by Brent's method; amplification factor
AF = Nc / (N2 - N1).  Required separation margin (API 617 / API 684 as commonly applied):
none for AF < 2.5; otherwise min(16, 17 (1 - 1/(AF - 1.5))) % below the operating range and
min(26, 10 + 17 (1 - 1/(AF - 1.5))) % above it.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from scipy.optimize import brentq, minimize_scalar
from scipy.sparse.csgraph import connected_components

from discrete.errors import ModelError
from discrete.linalg.banded import BandedLU

from .assembly import RotorSystem
from .model import Unbalance
from .modal import as_system
from .whirl import Orbits

PROBE_DIRECTIONS = ("v", "w", "major")
#: speeds per stacked band factorisation (memory ~ chunk * n * (3 b + 1) * 16 bytes)
CHUNK = 64


@dataclass
class Probe:
    """A response output: node at ``x`` (m), ``direction`` v | w | major (orbit semi-major axis)."""

    x: float
    direction: str = "major"
    name: str = ""
    """The output's name (default: the name of the disc, bearing or coupling at x, if it has one)."""

    def check(self, where: str) -> None:
        if self.direction not in PROBE_DIRECTIONS:
            raise ModelError(where, "direction", self.direction, " | ".join(map(repr, PROBE_DIRECTIONS)))


def place_name(rotor, x: float) -> str:
    """The name of the disc, bearing, coupling (or the pedestal-free support) at x, "" if none is named
    there (a rotor file's names in the outputs: docs/outputs.md)."""
    tol = 1e-9 * max(float(getattr(rotor, "length", 1.0)), 1e-300)
    for items in (rotor.discs, rotor.bearings, rotor.couplings):
        for it in items:
            if getattr(it, "name", "") and abs(float(it.x) - float(x)) <= tol:
                return it.name
    return ""


def probe_label(name: str, direction: str, x: float) -> str:
    return f"{name}.{direction}" if name else f"{direction}@x={x:g}"


@dataclass
class ProbeResponse:
    x: float
    direction: str
    amplitude: np.ndarray           # (n_speeds,) m (peak)
    phase_lag_deg: np.ndarray       # lag behind the shaft's reference mark (phase 0 of Unbalance), [0, 360)
    value: np.ndarray               # complex amplitude (v or w; forward circle component for "major")
    name: str = ""                  # the named thing at x (probe, disc, bearing, coupling), "" if none

    @property
    def label(self) -> str:
        """The output's name in JSON, CSV and legends: ``<name>.<direction>`` (``<direction>@x=<x>``
        where nothing at x has a name)."""
        return probe_label(self.name, self.direction, self.x)

    def to_dict(self) -> dict:
        return {"x": self.x, "direction": self.direction, "name": self.name, "label": self.label,
                "amplitude": self.amplitude.tolist(),
                "phase_lag_deg": self.phase_lag_deg.tolist(), "real": self.value.real.tolist(),
                "imag": self.value.imag.tolist()}


@dataclass
class ResponsePeak:
    """A resonance peak of one probe with its API 684-style figures (speeds rad/s, margins %)."""

    probe: int
    speed_rad_s: float
    amplitude: float
    half_power_rad_s: tuple | None
    amplification_factor: float | None
    separation_margin: float | None      # actual, % of the nearest operating-range limit
    required_margin: float | None        # API 617/684 requirement for this AF, %
    passes: bool | None
    note: str = ""
    resolved: bool = True                # False: the peak is bounded only by the search resolution (AF_RESOLVED)

    def to_dict(self) -> dict:
        return {"probe": self.probe, "speed_rad_s": self.speed_rad_s, "speed_rpm": self.speed_rad_s * 30 / np.pi,
                "amplitude": self.amplitude, "resolved": self.resolved,
                "half_power_rad_s": None if self.half_power_rad_s is None else list(self.half_power_rad_s),
                "amplification_factor": self.amplification_factor, "separation_margin_percent": self.separation_margin,
                "required_margin_percent": self.required_margin, "passes": self.passes, "note": self.note}


@dataclass
class UnbalanceResponse:
    """Synchronous response over ``speeds_rad_s``; ``response`` (n_speeds, n_dofs) complex."""

    speeds_rad_s: np.ndarray
    response: np.ndarray
    node_x: np.ndarray
    v_index: np.ndarray
    w_index: np.ndarray
    probes: list
    peaks: list
    operating_range: tuple | None
    n_dofs: int
    method: str
    warnings: list = field(default_factory=list)

    def orbits(self) -> Orbits:
        """Orbit ellipses, arrays (n_speeds, n_nodes)."""
        return Orbits.of(self.response[:, self.v_index], self.response[:, self.w_index])

    @property
    def shaft_amplitude(self) -> np.ndarray:
        """(n_speeds, n_nodes) semi-major axis of the orbit of every shaft node (m)."""
        return self.orbits().major

    def to_dict(self) -> dict:
        o = self.orbits()
        return {"speeds_rad_s": self.speeds_rad_s.tolist(), "speeds_rpm": (self.speeds_rad_s * 30 / np.pi).tolist(),
                "node_x": self.node_x.tolist(), "probes": [p.to_dict() for p in self.probes],
                "peaks": [p.to_dict() for p in self.peaks],
                "orbit_major": o.major.tolist(), "orbit_minor": o.minor.tolist(),
                "operating_range_rad_s": None if self.operating_range is None else list(self.operating_range),
                "n_dofs": self.n_dofs, "method": self.method, "warnings": list(self.warnings)}


#: The largest amplification factor a peak can be resolved with: the search locates the peak speed to 1e-9 of
#: itself, so a half-power band narrower than 1e-6 of the speed (AF > 1e6, a damping ratio below 5e-7) lies
#: within a thousand steps of that resolution -- an undamped (or practically undamped) mode, whose amplitude
#: grows without bound as the search closes in: its peak amplitude and AF are not properties of the rotor.
AF_RESOLVED = 1e6


def required_margin(af: float, above: bool) -> float:
    """API 617/684 separation margin (%) required for amplification factor ``af``."""
    if af < 2.5:
        return 0.0
    base = 17.0 * (1.0 - 1.0 / (af - 1.5))
    return min(26.0, 10.0 + base) if above else min(16.0, base)


class SynchronousSolver:
    """Solves (K - W^2 M + i W (C + W G)) Q = W^2 F at many speeds W on the block the load acts on.

    The band arrays of M, K, C, G are formed once; per chunk of speeds the stacked band
    matrices are combined by broadcasting (plus the tabulated bearing entries) and factorised
    by one ``zgbtrf`` call."""

    def __init__(self, rs: RotorSystem, load: np.ndarray):
        self.rs = rs
        free = np.ones(rs.n_dofs, dtype=bool)
        free[rs.constrained] = False
        P = rs.pattern
        P = sp.csr_matrix(P + P.T)
        _, labels = connected_components(P, directed=False)
        loaded = np.flatnonzero(load != 0)
        block = np.isin(labels, np.unique(labels[loaded])) & free
        self.idx = np.flatnonzero(block)
        pat = rs.pattern
        rows = np.repeat(np.arange(rs.n_dofs), np.diff(pat.indptr))
        self.sel = block[rows] & block[pat.indices]             # pattern entries inside the block
        self.layout = lay = BandedLU(sp.csr_matrix(pat[self.idx][:, self.idx]))
        self.data = {name: rs._on_pattern(A)[self.sel] for name, A in (("M", rs.M), ("K", rs.K0), ("C", rs.C0),
                                                                        ("G", rs.G))}
        if lay.banded:
            self.bands = {name: lay.to_band(d) for name, d in self.data.items()}
        if rs.tables:
            self.Bk = sp.csr_matrix(rs._Bk[self.sel])
            self.Bc = sp.csr_matrix(rs._Bc[self.sel])
            hit = np.flatnonzero(np.asarray(abs(self.Bk).sum(axis=1) + abs(self.Bc).sum(axis=1)).ravel())
            self.table_entries = hit
        self.load = np.asarray(load, dtype=complex)[self.idx]

    def solve(self, speeds: np.ndarray) -> np.ndarray:
        rs = self.rs
        s = np.atleast_1d(np.asarray(speeds, dtype=float))
        out = np.zeros((s.size, rs.n_dofs), dtype=complex)
        lay = self.layout
        for a in range(0, s.size, CHUNK):
            w = s[a:a + CHUNK]
            w2 = w**2
            if lay.banded:
                b = self.bands
                buf = np.empty((w.size, lay.n, lay.ldab), dtype=complex)
                buf.real[...] = b["K"][None] - w2[:, None, None] * b["M"][None]
                buf.imag[...] = w[:, None, None] * b["C"][None] + w2[:, None, None] * b["G"][None]
                if rs.tables:
                    c = rs.coefficients(w)
                    e = self.table_entries
                    kv = (self.Bk[e] @ c.T).T
                    cv = (self.Bc[e] @ c.T).T
                    buf[:, lay._band_col[e], lay._band_row[e]] += kv + 1j * w[:, None] * cv
                fac = lay.factor_band(buf)
            else:
                d = self.data
                K = rs.stiffness_data(w)[:, self.sel] if rs.tables else d["K"][None, :]
                C = rs.damping_data(w)[:, self.sel] if rs.tables else d["C"][None, :]
                Z = K - w2[:, None] * d["M"][None, :] + 1j * w[:, None] * C + 1j * w2[:, None] * d["G"][None, :]
                fac = lay.factor_many(Z)
            Q = fac.solve(w2[:, None] * self.load[None, :])
            out[a:a + CHUNK][:, self.idx] = Q
        return out


def unbalance_load(rs: RotorSystem, unbalances) -> np.ndarray:
    """F_u of the module notes (complex, full length; multiplied by Omega^2 at each speed)."""
    if isinstance(unbalances, Unbalance):
        unbalances = [unbalances]
    if not unbalances:
        raise ModelError("[[unbalance]]", "unbalance", [], "at least one unbalance")
    F = np.zeros(rs.n_dofs, dtype=complex)
    L = rs.rotor.length
    for i, u in enumerate(unbalances, 1):
        where = f"[[unbalance]] #{i}"
        if not isinstance(u, Unbalance):
            raise ModelError(where, "unbalance", u, "a fem.rotor.Unbalance(x, magnitude, phase)")
        u.check(where)
        if not -1e-12 * L <= u.x <= L * (1 + 1e-12):
            raise ModelError(where, "x", u.x, f"a position on the shaft, 0 <= x <= {L:g} m")
        e = u.magnitude * np.exp(1j * u.phase)
        F[rs.dof(u.x, "v", where)] += e
        F[rs.dof(u.x, "w", where)] += -1j * e
    return F


def _positive_speeds(speeds) -> np.ndarray:
    s = np.atleast_1d(np.asarray(speeds, dtype=float))
    if s.size < 2 or not np.all(np.isfinite(s)) or np.any(s <= 0) or np.any(np.diff(s) <= 0):
        raise ModelError("[analysis]", "speeds", s.tolist(), "at least two increasing speeds > 0 (rad/s)")
    return s


def _probe_values(Q: np.ndarray, rs: RotorSystem, probe: Probe):
    node = rs.node(probe.x)
    V, W = Q[..., rs.node_dofs["v"][node]], Q[..., rs.node_dofs["w"][node]]
    if probe.direction == "v":
        return np.abs(V), V
    if probe.direction == "w":
        return np.abs(W), W
    o = Orbits.of(V, W)
    return o.major, 0.5 * (V + 1j * W)


def unbalance_response(rotor, unbalances, speeds, *, probes=None, operating_range=None,
                       find_peaks: bool = True) -> UnbalanceResponse:
    """Synchronous unbalance response of ``rotor`` at ``speeds`` (rad/s, increasing, > 0).

    ``probes``: :class:`Probe` list (default: the orbit major axis at every disc and bearing);
    ``operating_range``: (min, max) operating speed in rad/s for the separation margins."""
    rs = as_system(rotor)
    s = _positive_speeds(speeds)
    F = unbalance_load(rs, unbalances)
    if probes is None:
        xs = sorted({round(d.x, 12) for d in rs.rotor.discs} | {round(b.x, 12) for b in rs.rotor.bearings})
        probes = [Probe(x, "major") for x in xs] or [Probe(rs.rotor.length / 2, "major")]
    for i, p in enumerate(probes, 1):
        if not isinstance(p, Probe):
            raise ModelError(f"[[probe]] #{i}", "probe", p, "a fem.rotor.response.Probe(x, direction)")
        p.check(f"[[probe]] #{i}")
        rs.node(p.x, f"[[probe]] #{i}")
    if operating_range is not None:
        lo, hi = (float(v) for v in operating_range)
        if not (np.isfinite(lo) and np.isfinite(hi) and 0 < lo <= hi):
            raise ModelError("[analysis]", "operating_range", list(operating_range), "(min, max) speeds with 0 < min <= max (rad/s)")
        operating_range = (lo, hi)
    solver = SynchronousSolver(rs, F)
    Q = solver.solve(s)
    lay = solver.layout
    method = (f"direct solve per speed on {solver.idx.size} DOFs, "
              + (f"stacked band LU (bandwidth {lay.bandwidth})" if lay.banded else "sparse LU (SuperLU)"))
    out = []
    for p in probes:
        amp, val = _probe_values(Q, rs, p)
        out.append(ProbeResponse(x=float(p.x), direction=p.direction, amplitude=amp,
                                 phase_lag_deg=np.mod(-np.degrees(np.angle(val)), 360.0), value=val,
                                 name=p.name or place_name(rs.rotor, p.x)))
    res = UnbalanceResponse(speeds_rad_s=s, response=Q, node_x=rs.node_x, v_index=rs.node_dofs["v"],
                            w_index=rs.node_dofs["w"], probes=out, peaks=[], operating_range=operating_range,
                            n_dofs=int(solver.idx.size), method=method)
    if find_peaks:
        for j, p in enumerate(probes):
            res.peaks += _peaks(solver, rs, p, j, s, out[j].amplitude, operating_range, res.warnings)
    return res


def _peaks(solver, rs, probe, j, s, amp, op_range, warnings) -> list:
    def a(speed):
        return float(_probe_values(solver.solve(np.array([speed]))[0], rs, probe)[0])

    peaks = []
    for i in range(1, s.size - 1):
        if not (amp[i] >= amp[i - 1] and amp[i] > amp[i + 1]):
            continue
        opt = minimize_scalar(lambda x: -a(x), bounds=(s[i - 1], s[i + 1]), method="bounded",
                              options={"xatol": 1e-9 * s[i]})
        nc, peak = float(opt.x), -float(opt.fun)
        if peak < amp[i]:
            nc, peak = float(s[i]), float(amp[i])
        target = peak / np.sqrt(2.0)
        # walk down each flank while the amplitude keeps falling; a flank that rises again (another
        # peak) before reaching peak/sqrt(2) has no half-power point: the peak is too broad for an AF
        lo = hi = None
        k = i
        while k > 0 and amp[k - 1] >= target and amp[k - 1] <= amp[k]:
            k -= 1
        if k > 0 and amp[k - 1] < target:
            lo = brentq(lambda x: a(x) - target, s[k - 1], nc if k == i else s[k], xtol=1e-10 * nc)
        k = i
        while k < s.size - 1 and amp[k + 1] >= target and amp[k + 1] <= amp[k]:
            k += 1
        if k < s.size - 1 and amp[k + 1] < target:
            hi = brentq(lambda x: a(x) - target, nc if k == i else s[k], s[k + 1], xtol=1e-10 * nc)
        note = ""
        af = sm = req = ok = None
        resolved = True
        if lo is not None and hi is not None and hi > lo and nc / (hi - lo) > AF_RESOLVED:
            resolved = False
            note = (f"UNBOUNDED: an undamped resonance (half-power band {hi - lo:.3g} rad/s, AF {nc / (hi - lo):.3g} "
                    f"> {AF_RESOLVED:g}): the amplitude grows without bound towards {nc:.6g} rad/s, the value shown "
                    "is where the search stopped; no AF, no margin check (add damping to the model)")
            warnings.append(f"probe {j + 1}: the peak near {nc * 30 / np.pi:.6g} rev/min is an undamped resonance: "
                            "its amplitude is bounded only by the search resolution (not reliable; add damping)")
        elif lo is not None and hi is not None and hi > lo:
            af = nc / (hi - lo)
        else:
            note = ("no half-power speeds on both flanks (the amplitude does not fall monotonically to peak/sqrt(2) "
                    "inside the speed range): a broad, well-damped peak or one at the range's edge; no AF")
        if op_range is not None:
            mn, mx = op_range
            if nc < mn:
                sm, above = 100.0 * (mn - nc) / mn, False
            elif nc > mx:
                sm, above = 100.0 * (nc - mx) / mx, True
            else:
                sm, above = -100.0 * min(nc - mn, mx - nc) / mx, nc > 0.5 * (mn + mx)
            if af is not None:
                req = required_margin(af, above)
                ok = bool(sm >= req) if req > 0 else True
        peaks.append(ResponsePeak(probe=j, speed_rad_s=nc, amplitude=peak,
                                  half_power_rad_s=None if lo is None or hi is None else (float(lo), float(hi)),
                                  amplification_factor=af, separation_margin=sm, required_margin=req, passes=ok,
                                  note=note, resolved=resolved))
    return peaks
