"""Linear forced response of a train over its speed: static transmission error and torque ripple.

At every reference speed Omega the train is the linear system of its declared state (meshes closed by
default) with each shaft's gyroscopic matrix and bearing coefficients at its own speed.  The loads are

* the constant parts of the [[force]] loads -> the static state q_s (K q_s = f_s; a train whose rotation
  is free is solved with inertia relief: q_s M-orthogonal to the rigid-body motions, the unbalanced
  torque accelerating the rigid train, K q_s = f_s - M R lam, R^T M q_s = 0);
* the harmonic parts of the loads at their frequency omega or at ``order`` times the speed of the member
  they act on (torque ripple), and every harmonic h of every closed mesh's static transmission error
  e(t) = e_h sin(h w_m t + phi_h) at h w_m (w_m = z_a |Omega_a|): the mesh force -k (s - e) - c (s' - e')
  loads the DOFs with (k + i w c) e_h e^(i phi_h) g.

Each harmonic is one complex solve (K + i w (C + Omega G) - w^2 M) Q = F (sparse LU); q(t) = q_s +
sum Im(Q e^(i w t)).  Outputs per speed: the force along every connection coordinate by the connection's
law (the mesh force: compression positive) as a static value, harmonic amplitudes, its peak over a
period and the dynamic load factor peak / |static|; every bearing's and support's force; the force
balance of every shaft and body for the static state and every harmonic.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from discrete.errors import ModelError, SolverError

from .assembly import TrainSystem
from .loads import balance, bearing_terms, internal_matrices, point_springs, rigid_directions


@dataclass
class TrainLoad:
    """A load on train DOF ``dof``: value + amplitude sin(w t + phase) with w = ``omega`` (rad/s) or
    ``order`` times |Omega_member| (torque ripple)."""

    dof: int
    value: float = 0.0
    amplitude: float = 0.0
    omega: float | None = None
    order: float | None = None
    member: str = ""
    phase: float = 0.0
    label: str = ""

    def frequency(self, ts: TrainSystem, speed: float) -> float:
        if self.order is not None:
            return self.order * abs(ts.ratios[self.member]) * float(speed)
        return float(self.omega or 0.0)


# ------------------------------------------------------------------ rigid-body motions
def rigid_candidates(ts: TrainSystem) -> np.ndarray:
    """Candidate rigid motions of every member (columns): axial translation, rotation about x, lateral
    translations and tilts of each shaft, rotation of each body."""
    n = ts.n_dofs
    cols = []
    for b in ts.blocks:
        sl = np.arange(b.offset, b.offset + b.n)
        f = ts.dof_field[sl]
        x = ts.dof_x[sl]
        for fields in (("u",), ("theta_x", "theta")):
            m = np.isin(f, fields)
            if m.any():
                c = np.zeros(n)
                c[sl[m]] = 1.0
                cols.append(c)
        if b.rs is not None:
            for disp, rot, sgn in (("v", "theta_z", 1.0), ("w", "theta_y", -1.0)):
                c = np.zeros(n)
                c[sl[f == disp]] = 1.0
                cols.append(c)
                c = np.zeros(n)
                c[sl[f == disp]] = x[f == disp]
                c[sl[f == rot]] = sgn
                cols.append(c)
        elif b.kind == "bending":
            rot = b.fe.model.fields[1]
            c = np.zeros(n)
            c[sl[f == "w"]] = 1.0
            cols.append(c)
            c = np.zeros(n)
            c[sl[f == "w"]] = x[f == "w"]
            c[sl[f == rot]] = 1.0
            cols.append(c)
    for i in range(len(ts.train.bodies)):
        c = np.zeros(n)
        c[ts.body_offset + i] = 1.0
        cols.append(c)
    return np.array(cols).T if cols else np.zeros((n, 0))


def rigid_modes(K: sp.spmatrix, constrained: np.ndarray, C: np.ndarray, tol: float = 1e-9) -> np.ndarray:
    """The rigid-body motions in the span of the candidates C: null space of [K C; C_held] (columns,
    orthonormal)."""
    if C.shape[1] == 0:
        return C
    KC = np.asarray(K @ C)
    scale = max(abs(K).max(), 1e-300) if sp.issparse(K) else max(np.abs(K).max(), 1e-300)
    A = np.vstack([KC / scale, C[constrained]])
    _, s, Vt = np.linalg.svd(A, full_matrices=True)
    s = np.concatenate([s, np.zeros(Vt.shape[0] - s.size)])
    null = Vt[s <= tol * max(s.max(initial=0.0), 1.0)].T
    if null.shape[1] == 0:
        return np.zeros((K.shape[0], 0))
    R = C @ null
    Q, _ = np.linalg.qr(R)
    return Q


def static_solve(K: sp.spmatrix, M: sp.spmatrix, f: np.ndarray, free: np.ndarray, R: np.ndarray) -> tuple:
    """(q_s, lam): K q = f - M R lam with R^T M q = 0 on the free DOFs (inertia relief when R has columns)."""
    n = K.shape[0]
    Kf = sp.csc_matrix(K[free][:, free])
    q = np.zeros(n)
    if R.shape[1] == 0:
        try:
            q[free] = spla.splu(Kf).solve(f[free])
        except RuntimeError as exc:
            raise SolverError(f"static state: the stiffness is singular ({exc}); the train floats in a way not "
                              "covered by its rigid-body motions") from None
        return q, np.zeros(0)
    MR = np.asarray(M[free] @ R)
    nr = R.shape[1]
    A = sp.bmat([[Kf, sp.csc_matrix(MR)], [sp.csc_matrix(MR.T), None]], format="csc")
    rhs = np.concatenate([f[free], np.zeros(nr)])
    sol = spla.splu(A).solve(rhs)
    q[free] = sol[:free.size]
    return q, sol[free.size:]


# ------------------------------------------------------------------ result
@dataclass
class ConnectionSeries:
    """The force along one connection coordinate over the speeds: ``static`` (N or N m), ``amplitude``
    (n_harmonics, n_speeds) of each harmonic, ``peak`` = max over a period of |static + dynamic|,
    ``dynamic_factor`` = peak / |static| (NaN when static is 0)."""

    connection: str
    coordinate: str
    static: float
    amplitude: np.ndarray
    peak: np.ndarray
    dynamic_factor: np.ndarray

    def to_dict(self) -> dict:
        return {"connection": self.connection, "coordinate": self.coordinate, "static": self.static,
                "amplitude": self.amplitude.tolist(), "peak": self.peak.tolist(),
                "dynamic_factor": [None if not np.isfinite(v) else float(v) for v in self.dynamic_factor]}


@dataclass
class TrainForcedResult:
    """Linear response over the reference speeds (see the module docstring)."""

    speeds_rad_s: np.ndarray
    harmonics: list                 # labels of the harmonic inputs
    frequencies: np.ndarray         # (n_harmonics, n_speeds), rad/s
    connections: list               # ConnectionSeries
    bearings: dict                  # label -> {"static": (3,), "peak_radial": (n_speeds,), "amplitude": (3, nh, ns)}
    supports: dict                  # label -> {"static": float, "peak": (n_speeds,)}
    static_state: np.ndarray
    rigid_acceleration: np.ndarray
    balance_max: float
    balance: dict
    window_note: str = ""
    warnings: list = field(default_factory=list)

    def mesh(self, name: str, coordinate: str | None = None) -> ConnectionSeries:
        for c in self.connections:
            if c.connection == name and (coordinate is None or c.coordinate == coordinate):
                return c
        raise ModelError("result", "connection", name, "one of " + ", ".join(sorted({c.connection for c in
                                                                                         self.connections})))

    def static_section_loads(self, ts) -> dict:
        """{shaft: :class:`fem.loads.SectionLoads` of the static state} (fem.loads per shaft)."""
        from .loads import shaft_section_loads

        return {b.name: shaft_section_loads(ts, b.name, self.static_state) for b in ts.blocks}

    def to_dict(self) -> dict:
        return {"speeds_rad_s": self.speeds_rad_s.tolist(), "speeds_rpm": (self.speeds_rad_s * 30 / math.pi).tolist(),
                "harmonics": list(self.harmonics), "harmonic_frequencies_rad_s": self.frequencies.tolist(),
                "connections": [c.to_dict() for c in self.connections],
                "bearings": {k: {"static": np.asarray(v["static"]).tolist(), "peak_radial": v["peak_radial"].tolist()}
                             for k, v in self.bearings.items()},
                "supports": {k: {"static": v["static"], "peak": v["peak"].tolist()} for k, v in self.supports.items()},
                "rigid_acceleration": self.rigid_acceleration.tolist(), "force_balance": self.balance,
                "force_balance_max_residual": self.balance_max, "window_note": self.window_note,
                "warnings": list(self.warnings)}


def _window(freqs: np.ndarray, samples: int) -> tuple[np.ndarray, str]:
    """Times covering one common period of the harmonics (or 20 periods of the lowest when incommensurate)."""
    f = freqs[freqs > 0]
    if f.size == 0:
        return np.zeros(1), ""
    w0 = f.min()
    ratio = f / w0
    if np.all(np.abs(ratio - np.round(ratio)) <= 1e-9 * ratio):
        n = int(samples * max(1, int(round(ratio.max()))))
        return np.arange(n) * (2 * math.pi / w0) / n, ""
    n = int(samples * 20 * max(1.0, float(ratio.max())))
    return np.arange(n) * (40 * math.pi / w0) / n, ("harmonics not commensurate: peaks over 20 periods of the "
                                                    "lowest harmonic")


def train_forced(ts: TrainSystem, speeds, loads: list[TrainLoad] = (), *, samples: int = 64) -> TrainForcedResult:
    """The linear response at every reference speed in ``speeds`` (rad/s) to ``loads`` and the meshes'
    transmission error (see the module docstring)."""
    speeds = np.atleast_1d(np.asarray(speeds, float))
    if speeds.size == 0 or not np.all(np.isfinite(speeds)) or np.any(speeds < 0):
        raise ModelError("[forced]", "speeds", speeds.tolist(), "speeds >= 0 (rad/s)")
    n = ts.n_dofs
    free = np.setdiff1d(np.arange(n), ts.constrained)
    M = ts.M
    Kint, Cint = internal_matrices(ts)
    Kpts = point_springs(ts)
    dirs = rigid_directions(ts)
    conns = [(c, cd) for c in ts.train.connections for cd in ts.connection_coords[c.name]]
    sizes = []
    rows_h, freqs_all = None, []
    series = {(c.name, cd.label): {"amp": [], "peak": [], "static": 0.0} for c, cd in conns}
    bear_out, supp_out = {}, {}
    worst = 0.0
    bal_rows = {}
    note = ""
    warnings = list(ts.warnings)
    f_static = np.zeros(n)
    for ld in loads:
        f_static[ld.dof] += ld.value
    q_s = lam = None
    for js, speed in enumerate(speeds):
        K = ts.stiffness(speed)
        C = ts.damping(speed) + speed * ts.G
        if js == 0 or ts.speed_dependent:
            R = rigid_modes(K, ts.constrained, rigid_candidates(ts))
            q_s, lam = static_solve(K, M, f_static, free, R)
        # harmonic inputs at this speed
        inputs = []
        for ld in loads:
            if ld.amplitude:
                w = ld.frequency(ts, speed)
                F = np.zeros(n, complex)
                F[ld.dof] = ld.amplitude * np.exp(1j * ld.phase)
                inputs.append((ld.label or f"load@{ts.label(ld.dof)}", w, F, {}))
        for c in ts.train.connections:
            if c.linear_state == "open":
                continue
            for ex in c.excitations(ts, speed):
                w = ex.omega
                E = ex.amplitude * np.exp(1j * ex.phase)
                F = np.zeros(n, complex)
                np.add.at(F, ex.coord.idx, (ex.stiffness + 1j * w * ex.damping) * E * ex.coord.val)
                inputs.append((f"{c.name} transmission error h{ex.harmonic}", w, F, {c.name: E}))
        if rows_h is None:
            rows_h = [lab for lab, *_ in inputs]
        elif [lab for lab, *_ in inputs] != rows_h:     # pragma: no cover - the inputs do not depend on speed
            raise SolverError("the harmonic inputs changed with the speed")
        sizes.append(len(inputs))
        freqs = np.array([w for _, w, _, _ in inputs])
        freqs_all.append(freqs)
        t, note_s = _window(freqs, samples)
        note = note or note_s
        Qs = []
        for lab, w, F, exo in inputs:
            Z = sp.csc_matrix((K + 1j * w * C - w * w * M)[free][:, free])
            Q = np.zeros(n, complex)
            try:
                lu = spla.splu(Z)
                x = lu.solve(F[free])
                x = x + lu.solve(F[free] - Z @ x)            # one step of iterative refinement
                Q[free] = x
            except RuntimeError:
                raise SolverError(f"speed {speed:.6g} rad/s, {lab}: the dynamic stiffness is singular at "
                                  f"omega = {w:.6g} rad/s (an undamped resonance)") from None
            Qs.append((Q, w, exo))
        # connections
        for c, cd in conns:
            s_static = cd.of(q_s)
            Fs = -cd.k * s_static
            amps, hist = [], np.full(t.size, Fs, dtype=float)
            for Q, w, exo in Qs:
                e = exo.get(c.name, 0.0) if cd.label == "line of action" else 0.0
                Fh = -(cd.k + 1j * w * cd.c) * (cd.of(Q) - e)
                amps.append(abs(Fh))
                hist = hist + np.imag(Fh * np.exp(1j * w * t))
            sgn = -1.0 if c.table == "mesh" else 1.0        # mesh force: compression positive
            rec = series[(c.name, cd.label)]
            rec["static"] = sgn * Fs
            rec["amp"].append(amps)
            rec["peak"].append(float(np.max(np.abs(hist))))
        # bearings
        for bt in bearing_terms(ts, speed):
            fs = bt.force(q_s, np.zeros(n))[:, 0]
            hist = np.repeat(fs[:, None], t.size, axis=1)
            amp = []
            for Q, w, _ in Qs:
                fh = bt.force(Q, 1j * w * Q)[:, 0]
                amp.append(np.abs(fh))
                hist = hist + np.imag(fh[:, None] * np.exp(1j * w * t)[None, :])
            rec = bear_out.setdefault(bt.label, {"static": fs, "peak_radial": [], "amplitude": []})
            rec["static"] = fs
            rec["peak_radial"].append(float(np.max(np.hypot(hist[0], hist[1]))))
            rec["amplitude"].append(np.array(amp).T if amp else np.zeros((3, 0)))
        # supports (held DOFs): R_c = (K q - f)_c, harmonics (Z Q - F)_c
        for j in ts.constrained:
            r_s = float((K @ q_s)[j] - f_static[j])
            hist = np.full(t.size, r_s)
            for (Q, w, _), (_, _, F, _) in zip(Qs, inputs):
                rh = ((K + 1j * w * C - w * w * M) @ Q)[j] - F[j]
                hist = hist + np.imag(rh * np.exp(1j * w * t))
            rec = supp_out.setdefault(ts.label(j), {"static": r_s, "peak": []})
            rec["static"] = r_s
            rec["peak"].append(float(np.max(np.abs(hist))))
        # force balance: static state and every harmonic
        bts = bearing_terms(ts, speed)
        cases = [(q_s, np.zeros(n), -(M @ _rigid_part(R, lam)), f_static, None, {})]
        # a transmission error's load is the mesh force's exogenous part (counted with the mesh), not applied
        cases += [(Q, 1j * w * Q, -w * w * Q, np.zeros(n, complex) if exo else F, w, exo)
                  for (Q, w, exo), (_, _, F, _) in zip(Qs, inputs)]
        for q, v, a, f, w, exo in cases:
            terms = _terms(ts, q, v, a, f, M, Kint, Cint + speed * ts.G, Kpts, bts, conns, w, exo)
            b = balance(ts, dirs, {k: np.atleast_1d(V) for k, V in terms.items()})
            worst = max(worst, b.max_residual)
            for row in b.rows:
                key = (row["member"], row["direction"])
                bal_rows[key] = max(bal_rows.get(key, 0.0), row["residual"])
    nh = len(rows_h or [])
    out_series = [ConnectionSeries(connection=c.name, coordinate=cd.label, static=float(series[(c.name, cd.label)]["static"]),
                                   amplitude=np.array(series[(c.name, cd.label)]["amp"]).reshape(speeds.size, nh).T,
                                   peak=np.array(series[(c.name, cd.label)]["peak"]),
                                   dynamic_factor=(np.array(series[(c.name, cd.label)]["peak"]) /
                                                   abs(series[(c.name, cd.label)]["static"])
                                                   if series[(c.name, cd.label)]["static"] else
                                                   np.full(speeds.size, np.nan)))
                  for c, cd in conns]
    for rec in bear_out.values():
        rec["peak_radial"] = np.array(rec["peak_radial"])
    for rec in supp_out.values():
        rec["peak"] = np.array(rec["peak"])
    balance_dict = {"max_residual": worst, "rows": [{"member": m, "direction": d, "residual": r}
                                                     for (m, d), r in bal_rows.items()]}
    return TrainForcedResult(speeds_rad_s=speeds, harmonics=list(rows_h or []),
                             frequencies=np.array(freqs_all).reshape(speeds.size, nh).T, connections=out_series,
                             bearings=bear_out, supports=supp_out, static_state=q_s,
                             rigid_acceleration=np.asarray(lam, float), balance_max=worst, balance=balance_dict,
                             window_note=note, warnings=warnings)


def _rigid_part(R, lam):
    return R @ lam if R.shape[1] else np.zeros(R.shape[0])


def _terms(ts, q, v, a, f, M, Kint, Cint, Kpts, bts, conns, w, exo) -> dict:
    """The force vectors on the DOFs whose sum vanishes (module docstring of :mod:`.loads`): static state
    (w None) or a harmonic of frequency w (complex amplitudes, v = i w q, a = -w^2 q)."""
    n = ts.n_dofs
    dt = np.result_type(q, v, a, f)
    bear = np.zeros(n, dt)
    for bt in bts:
        fb = bt.force(q, v)[:, 0]
        bear[bt.shaft_dofs[0]] += fb[0]
        bear[bt.shaft_dofs[1]] += fb[1]
        if bt.axial_dof is not None:
            bear[bt.axial_dof] += fb[2]
    conn = {}
    for c, cd in conns:
        if w is None:
            Fc = -cd.k * cd.of(q)
        else:
            e = exo.get(c.name, 0.0) if cd.label == "line of action" else 0.0
            Fc = -(cd.k + 1j * w * cd.c) * (cd.of(q) - e)
        vec = np.zeros(n, dt)
        np.add.at(vec, cd.idx, cd.val * Fc)
        conn[f"{c.name}:{cd.label}"] = vec
    inertia = -(M @ a)
    damping = -(Cint @ v)
    elastic = -(Kint @ q)
    springs = -(Kpts @ q)
    held = np.zeros(n, dt)
    tot = inertia + damping + elastic + springs + bear + sum(conn.values(), np.zeros(n, dt)) + f
    held[ts.constrained] = -tot[ts.constrained]
    return {"inertia": inertia, "damping": damping, "elastic": elastic, "springs": springs, "bearings": bear,
            **conn, "applied": f, "supports": held}
