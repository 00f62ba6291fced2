"""Modal and forced analysis of a drive by its three representations, and their comparison.

* ``discrete``: the FE/lumped :class:`LinearSystem` (sparse shift-invert modal analysis,
  direct harmonic solve); reference: the regular-structure closed forms (lumped shaft).
* ``transfer-matrix``: the chain of :mod:`discrete.transfer` (count bisection, normalised
  line sweep); exact for a lumped shaft and for a continuous shaft with discrete mechanisms.
* ``continuum``: the two-field pseudo-medium in scikit-fem; reference: (10.50) and the
  corrected (10.59)-(10.61).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from discrete.errors import ModelError
from discrete.transfer import RegularDrive, forced_response, mode_shape, natural_frequencies
from discrete.transfer.continuum import pseudo_medium_forced, stop_band

from .continuum import build_continuum
from .discrete import build_discrete
from .model import DistributedShaft, DriveModel
from .seeding import continuum_estimates, continuum_roots, continuum_sorted, seedable
from .tm import build_chain



# ------------------------------------------------------------------ helpers
def regular_of(model: DriveModel) -> RegularDrive | None:
    """The closed-form regular structure of a lumped-shaft drive (None for a distributed shaft)."""
    if isinstance(model.shaft, DistributedShaft):
        return None
    me = model.mechanism
    return RegularDrive(n=model.n, c0=model.shaft.c0, J0=model.shaft.J0, m=me.m, c=me.c, ratio=me.ratio,
                        boundary=model.boundary, output=me.output)


def _tm_scale(model: DriveModel) -> float:
    """Starting guess of the upper bracket: half the partial frequency (1 rad/s for rigid mechanisms)."""
    return 1.0 if model.mechanism.rigid else 0.5 * model.mechanism.k


def _eig_above(system, sigma: float, R: int) -> np.ndarray:
    """The R natural frequencies just above sigma (rad^2/s^2): shift-invert Lanczos with
    which = 'LA' (largest 1/(lam - sigma) > 0), used for the upper branch above the stop band
    without computing the crowd of lower-branch modes below it."""
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla

    K, M = system.free_block(system.K), system.free_block(system.M)
    lu = spla.splu(sp.csc_matrix(K - sigma * M))
    op = spla.LinearOperator(K.shape, matvec=lu.solve, dtype=float)
    lam = spla.eigsh(K, k=R, M=M, sigma=sigma, which="LA", OPinv=op, ncv=min(K.shape[0], max(2 * R + 1, 20)),
                     return_eigenvectors=False)
    return np.sqrt(np.sort(lam))


def fe_modes(model: DriveModel, system, n_modes: int):
    """Sparse FE modal analysis of the discrete drive.  Large drives crowd their lower-branch
    roots below k, where shift-invert Lanczos needs hundreds of iterations: there the
    certified seeded solver starts from the pseudo-medium estimates (:mod:`.seeding`)."""
    from discrete.linear.modal import modal_analysis

    if seedable(model, system, n_modes):
        lam, rows = continuum_estimates(model, system, n_modes + 1)
        return modal_analysis(system, n_modes, seeds=lam, seed_vectors=rows)
    return modal_analysis(system, n_modes)


# ------------------------------------------------------------------ modal
@dataclass
class DriveModalResult:
    omega_rad_s: np.ndarray
    residuals: np.ndarray
    n_dofs: int
    representation: str
    method: str
    description: str
    reference_omega: np.ndarray | None = None
    reference: str = ""
    stop_band_rad_s: tuple | None = None
    residual_kind: str = ""
    warnings: list = field(default_factory=list)
    modal: object = None               # the FE ModalResult (discrete and continuum representations)
    shapes: dict | None = None         # {"dofs": labels, "modes": [[...], ...]} where available

    RESIDUAL_LIMIT = 1e-6

    @property
    def frequencies_hz(self) -> np.ndarray:
        return self.omega_rad_s / (2 * np.pi)

    @property
    def reliable(self) -> np.ndarray:
        """Per mode: the FE modal checks (FE representations) or residual < 1e-6 (transfer matrices)."""
        if self.modal is not None:
            return self.modal.reliable | self.modal.rigid
        return np.asarray(self.residuals) < self.RESIDUAL_LIMIT

    @property
    def ok(self) -> bool:
        """All residuals below 1e-6 (for the CLI exit code)."""
        return bool(np.all(np.asarray(self.residuals) < self.RESIDUAL_LIMIT))

    @property
    def rel_diff(self) -> np.ndarray | None:
        if self.reference_omega is None:
            return None
        ref = self.reference_omega
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.where(ref > 0, np.abs(self.omega_rad_s - ref) / np.where(ref > 0, ref, 1), np.abs(self.omega_rad_s))

    def to_dict(self) -> dict:
        d = {"omega_rad_s": self.omega_rad_s.tolist(), "frequencies_hz": self.frequencies_hz.tolist(),
             "n_dofs": int(self.n_dofs), "n_modes": int(self.omega_rad_s.size), "residuals": self.residuals.tolist(),
             "residual_kind": self.residual_kind, "representation": self.representation, "method": self.method,
             "description": self.description, "warnings": list(self.warnings),
             "stop_band_rad_s": None if self.stop_band_rad_s is None else list(self.stop_band_rad_s)}
        if self.reference_omega is not None:
            d["reference"] = self.reference
            d["reference_omega_rad_s"] = self.reference_omega.tolist()
            d["rel_diff"] = self.rel_diff.tolist()
        return d

    def table(self) -> str:
        lines = [self.description, f"representation: {self.representation} ({self.method}); {self.n_dofs} DOFs",
                 f"residual: {self.residual_kind}"]
        if self.stop_band_rad_s is not None:
            lines.append(f"stop band (J* < 0, no natural frequency): {self.stop_band_rad_s[0]:.6g} .. "
                         f"{self.stop_band_rad_s[1]:.6g} rad/s")
        hdr = f"{'mode':>5} {'omega [rad/s]':>16} {'f [Hz]':>14} {'residual':>10}"
        if self.reference_omega is not None:
            hdr += f" {'reference':>16} {'rel.diff':>9}"
            lines.append(f"reference: {self.reference}")
        lines.append(hdr)
        rd = self.rel_diff
        for i, w in enumerate(self.omega_rad_s):
            row = f"{i + 1:>5} {w:>16.8g} {w / (2 * np.pi):>14.8g} {self.residuals[i]:>10.2e}"
            if self.reference_omega is not None:
                row += f" {self.reference_omega[i]:>16.8g} {rd[i]:>9.1e}"
            lines.append(row)
        lines += [f"warning: {w}" for w in self.warnings]
        return "\n".join(lines)


def modal(model: DriveModel, n_modes: int, representation: str | None = None) -> DriveModalResult:
    """Lowest ``n_modes`` natural frequencies of ``model`` by one representation."""
    from discrete.linear.modal import modal_analysis

    rep = representation or model.representation
    reg = regular_of(model)
    sb = None
    sm = model.smeared()
    if model.mechanism.output == "free" and not sm["rigid"] and sm["rho"] > 0 and (reg is not None or rep == "continuum"):
        sb = stop_band(sm["rho"], sm["m_bar"], sm["k"], sm["ratio"])
    ref, ref_name = None, ""
    if rep == "continuum":
        cd = build_continuum(model)
        res = modal_analysis(cd.system, n_modes)
        omega, resid, ndof, fe_res = res.omega_rad_s, res.residuals, res.n_dofs, res
        shapes = {"dofs": cd.system.labels(), "modes": res.shapes.T.tolist()}
        method = f"two-field pseudo-medium, P{model.continuum_order} x {model.continuum_elements} elements; {res.method}"
        kind, warn = "FE backward error ||K phi - lam M phi|| / ((||K|| + lam ||M||) ||phi||)", res.warnings
        if cd.params["rho"] > 0:
            ref, ref_name = continuum_sorted(model, n_modes), "pseudo-medium closed form (10.50) (exact continuum)"
    elif rep == "discrete":
        dd = build_discrete(model)
        res = fe_modes(model, dd.system, n_modes)
        omega, resid, ndof, fe_res = res.omega_rad_s, res.residuals, res.n_dofs, res
        shapes = {"dofs": dd.system.labels(), "modes": res.shapes.T.tolist()}
        kind, warn = "FE backward error ||K phi - lam M phi|| / ((||K|| + lam ||M||) ||phi||)", res.warnings
        method = res.method + ("" if reg else f"; shaft P{model.shaft.order}, {model.shaft.elements} el./segment")
    else:
        chain, _, _ = build_chain(model)
        roots = natural_frequencies(chain, n_modes, p_guess=_tm_scale(model))
        omega, resid, fe_res = roots.omega_rad_s, roots.newton_rel, None
        shapes = _tm_shapes(chain, omega)
        per = 1 if (model.mechanism.rigid or model.mechanism.output == "grounded") else 2
        ndof = per * model.n if reg is not None else 2 * (len(chain.elements) + 1)
        method = f"transfer matrices: Wittrick-Williams count bisection, normalised line sweep ({roots.evaluations} sweeps)"
        kind = ("relative root error implied by the boundary residual, |f/(p f')|, f = normalised end-line "
                "component (pole-free, |f| <= 1)")
        warn = []
        if reg is None:
            warn.append("n_dofs for a continuous shaft: 2 state components per section (the shaft itself is exact)")
    if reg is not None and rep != "continuum":
        allf = reg.natural_frequencies()
        if allf.size >= n_modes:
            ref, ref_name = allf[:n_modes], "regular-structure closed form (10.36) with (10.16) (exact)"
    elif reg is None and rep == "discrete":
        chain, _, _ = build_chain(model)
        ref = natural_frequencies(chain, n_modes, p_guess=_tm_scale(model)).omega_rad_s
        ref_name = "transfer matrices with exact continuous shaft segments (FE discretisation error shown)"
    return DriveModalResult(omega_rad_s=np.asarray(omega), residuals=np.asarray(resid), n_dofs=int(ndof),
                            representation=rep, method=method, description=model.describe(), reference_omega=ref,
                            reference=ref_name, stop_band_rad_s=sb, residual_kind=kind, warnings=list(warn),
                            modal=fe_res, shapes=shapes)


def _tm_shapes(chain, omega) -> dict:
    """Section amplitudes of every transfer-matrix mode, normalised to the largest magnitude."""
    modes = []
    for w in omega:
        a = np.real(mode_shape(chain, float(w)).a).ravel()
        peak = np.max(np.abs(a)) if a.size else 0.0
        modes.append((a / peak if peak > 0 else a).tolist())
    n = len(modes[0]) if modes else 0
    return {"dofs": [f"section {i}" for i in range(n)], "modes": modes}


# ------------------------------------------------------------------ forced
@dataclass
class DriveForcedResult:
    omega_rad_s: np.ndarray
    x_stations: np.ndarray
    theta: np.ndarray              # (n_freq, n) complex shaft amplitude at the stations
    y: np.ndarray                  # (n_freq, n) complex mechanism-output amplitude
    representation: str
    method: str
    damping: str
    description: str
    force: float
    reference_theta: np.ndarray | None = None
    reference: str = ""
    warnings: list = field(default_factory=list)

    @property
    def frequencies_hz(self):
        return self.omega_rad_s / (2 * np.pi)

    def to_dict(self) -> dict:
        d = {"omega_rad_s": self.omega_rad_s.tolist(), "frequencies_hz": self.frequencies_hz.tolist(),
             "x_stations": self.x_stations.tolist(), "representation": self.representation, "method": self.method,
             "damping": self.damping, "description": self.description, "force": self.force,
             "theta_real": self.theta.real.tolist(), "theta_imag": self.theta.imag.tolist(),
             "theta_amplitude": np.abs(self.theta).tolist(), "y_amplitude": np.abs(self.y).tolist(),
             "y_real": self.y.real.tolist(), "y_imag": self.y.imag.tolist(), "warnings": list(self.warnings)}
        if self.reference_theta is not None:
            d["reference"] = self.reference
            d["reference_theta"] = self.reference_theta.tolist()
        return d

    def write_csv(self, path) -> None:
        """omega, then Re/Im of theta at every station and of y at every output."""
        n = self.theta.shape[1]
        cols = [self.omega_rad_s, self.frequencies_hz]
        head = ["omega_rad_s", "f_hz"]
        for name, arr in (("theta", self.theta), ("y", self.y)):
            for j in range(n):
                cols += [arr[:, j].real, arr[:, j].imag]
                head += [f"{name}{j + 1}_re", f"{name}{j + 1}_im"]
        np.savetxt(path, np.column_stack(cols), delimiter=",", header=",".join(head), comments="")

    def table(self) -> str:
        lines = [self.description, f"forced response: {self.representation} ({self.method}); damping: {self.damping}; "
                 f"force {self.force:g} N on every mechanism output",
                 "theta_j: shaft amplitude at station j (signed real part; |.| if damped), y_n: last mechanism output"]
        hdr = f"{'omega [rad/s]':>14} {'theta_1':>13} {'theta_mid':>13} {'theta_n':>13} {'y_n':>13}"
        if self.reference_theta is not None:
            hdr += f" {'ref theta_n':>13} {'rel.diff':>9}"
            lines.append(f"reference: {self.reference}")
        lines.append(hdr)
        damped = np.abs(self.theta.imag).max() > 1e-12 * np.abs(self.theta).max()
        val = (lambda z: np.abs(z)) if damped else (lambda z: z.real)
        n = self.theta.shape[1]
        for i, w in enumerate(self.omega_rad_s):
            row = (f"{w:>14.6g} {val(self.theta[i, 0]):>13.5e} {val(self.theta[i, (n - 1) // 2]):>13.5e} "
                   f"{val(self.theta[i, -1]):>13.5e} {val(self.y[i, -1]):>13.5e}")
            if self.reference_theta is not None:
                r = self.reference_theta[i, -1]
                row += f" {r:>13.5e} {abs(self.theta[i, -1] - r) / max(abs(r), 1e-300):>9.1e}"
            lines.append(row)
        lines += [f"warning: {w}" for w in self.warnings]
        return "\n".join(lines)


def forced(model: DriveModel, omegas, representation: str | None = None, delta: float = 0.0,
           damping_name: str = "undamped") -> DriveForcedResult:
    """Steady-state response to the force ``model.force`` on every mechanism output."""
    from discrete.linear.harmonic import Damping, harmonic_response

    rep = representation or model.representation
    omegas = np.atleast_1d(np.asarray(omegas, dtype=float))
    if model.mechanism.rigid:
        raise ModelError("[drive.mechanism]", "c", "inf", "elastic mechanisms (finite c or k) for the forced response")
    if model.force == 0:
        raise ModelError("[drive.load]", "force", 0.0, "a non-zero force amplitude on the mechanism outputs")
    xs = model.stations()
    if model.mechanism.output == "grounded":
        raise ModelError("[drive.mechanism]", "output", "grounded",
                         "'free' for a force on the mechanism outputs (a grounded output does not move)")
    if rep == "discrete":
        dd = build_discrete(model, delta=delta)
        F = np.zeros(dd.system.n_dofs, dtype=complex)
        F[dd.y] = model.force
        res = harmonic_response(dd.system, omegas, force=F, damping=Damping(type="viscous" if delta else "none"),
                                outputs=list(dd.theta) + list(dd.y))
        theta, y = res.response[:, :model.n], res.response[:, model.n:]
        method = "direct sparse solve of the FE/lumped system"
    elif rep == "transfer-matrix":
        chain, discs, branches = build_chain(model, load=model.force, delta=delta)
        r = forced_response(chain, omegas)
        theta = r.a[:, discs]
        y = np.column_stack([r.branch_a[b] for b in branches])
        method = "transfer matrices: normalised line sweep with loads, stable back-substitution ((10.22)-(10.27))"
    else:
        cd = build_continuum(model, delta=delta)
        res = harmonic_response(cd.system, omegas, force=cd.load.astype(complex),
                                damping=Damping(type="viscous" if delta else "none"))
        q = res.response.T   # (n_dofs, n_freq)
        theta = np.asarray(cd.values_at(q, xs, "theta")).T
        y = np.asarray(cd.values_at(q, xs, "y")).T
        method = (f"two-field pseudo-medium P{model.continuum_order} x {model.continuum_elements} el., direct solve; "
                  "values at the stations interpolated")
    ref, ref_name = None, ""
    reg = regular_of(model)
    if delta == 0 and model.mechanism.output == "free" and np.all(np.asarray(omegas) > 0):
        # (10.40)-(10.46) and the pseudo-medium form divide by w^2: no reference at w = 0 (a static load)
        if rep != "continuum" and reg is not None and model.boundary in ("clamped-free", "clamped-clamped"):
            ref = np.array([reg.forced_amplitudes(w, model.force) for w in omegas])
            ref_name = "corrected closed form of (10.40)-(10.46) (regular structure)"
        elif rep == "continuum" and model.boundary == "clamped-free":
            s = model.smeared()
            fb = model.n * model.force / s["L"]
            ref = np.array([pseudo_medium_forced(xs, w, s["GI"], s["rho"], s["m_bar"], s["k"], s["ratio"], s["L"], fb)
                            for w in omegas])
            ref_name = "corrected pseudo-medium solution (10.58)-(10.61), f_bar = n F / L"
    return DriveForcedResult(omega_rad_s=omegas, x_stations=xs, theta=theta, y=y, representation=rep, method=method,
                             damping=damping_name, description=model.describe(), force=model.force,
                             reference_theta=ref, reference=ref_name)


# ------------------------------------------------------------------ comparison
def _branches(omega: np.ndarray, k: float, R: int) -> tuple[np.ndarray, np.ndarray]:
    """The first R roots below and above k; a root at k itself (to round-off: the continuum's
    mode at the mechanism frequency) belongs to neither branch."""
    omega = np.sort(omega[(omega > 0) & (np.abs(omega / k - 1) >= 1e-9)])
    lo, hi = omega[omega < k][:R], omega[omega > k][:R]
    pad = lambda a: np.concatenate([a, np.full(R - a.size, np.nan)])
    return pad(lo), pad(hi)


def branch_roots(model: DriveModel, representation: str, R: int) -> tuple[np.ndarray, np.ndarray]:
    """(lower, upper) branch roots r = 1..R (lower: below k, in-phase; upper: above p_*)."""
    from discrete.linear.modal import modal_analysis

    k = model.mechanism.k
    if representation == "transfer-matrix":
        chain, _, _ = build_chain(model)
        lo = natural_frequencies(chain, min(R, model.n), p_guess=_tm_scale(model)).omega_rad_s
        from discrete.transfer import count_below
        n_k = int(count_below(chain, k * (1 + 1e-9))[0])
        hi = natural_frequencies(chain, n_k + R, p_guess=k).omega_rad_s[n_k:]
        return _branches(np.concatenate([lo, hi]), k, R)
    if representation == "discrete":
        sys_ = build_discrete(model).system
    else:
        cd = build_continuum(model)
        sys_ = cd.system
        if cd.params["rho"] == 0:
            raise ModelError("[drive.shaft]", "rho", 0.0, "a shaft with inertia for the continuum upper branch")
    if sys_.n_free <= 300:
        n_y = int(np.count_nonzero(sys_.dof_field[sys_.free] == "y"))
        res = modal_analysis(sys_, min(sys_.n_free, n_y + R + (model.boundary == "free-free")))
        return _branches(res.omega_rad_s, k, R)
    low = (fe_modes(model, sys_, R + (model.boundary == "free-free")) if representation == "discrete"
           else modal_analysis(sys_, R + (model.boundary == "free-free"))).omega_rad_s
    s = model.smeared()
    edge = stop_band(s["rho"], s["m_bar"], s["k"], s["ratio"])[1] if s["rho"] > 0 else k
    return _branches(np.concatenate([low, _eig_above(sys_, edge**2, R)]), k, R)


@dataclass
class DriveComparison:
    description: str
    R: int
    rows: dict                       # name -> (lower[R], upper[R])
    convergence_n: np.ndarray
    convergence_lower: np.ndarray    # (len(n), R) discrete roots
    convergence_upper: np.ndarray
    continuum_lower: np.ndarray
    continuum_upper: np.ndarray
    convergence_source: str = ""

    @property
    def convergence_rel(self) -> tuple[np.ndarray, np.ndarray]:
        """Relative deviations of the discrete roots from the continuum's (NaN for a rigid-body root, 0 in both)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return (np.where(self.continuum_lower != 0, self.convergence_lower / self.continuum_lower - 1, np.nan),
                    np.where(self.continuum_upper != 0, self.convergence_upper / self.continuum_upper - 1, np.nan))

    @property
    def observed_order(self) -> np.ndarray:
        """log2 of successive error ratios of the lower/upper r = 1 roots (n doubling)."""
        e = np.abs(np.column_stack([self.convergence_rel[0][:, 0], self.convergence_rel[1][:, 0]]))
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.log(e[:-1] / e[1:]) / np.log(self.convergence_n[1:] / self.convergence_n[:-1])[:, None]

    def to_dict(self) -> dict:
        lo_rel, hi_rel = self.convergence_rel
        nan = lambda a: [None if not np.isfinite(v) else float(v) for v in np.ravel(a)]
        return {"description": self.description, "R": self.R,
                "representations": {k: {"lower_rad_s": nan(v[0]), "upper_rad_s": nan(v[1])} for k, v in self.rows.items()},
                "convergence": {"n": self.convergence_n.tolist(), "source": self.convergence_source,
                                "lower_rad_s": self.convergence_lower.tolist(),
                                "upper_rad_s": self.convergence_upper.tolist(),
                                "continuum_lower_rad_s": self.continuum_lower.tolist(),
                                "continuum_upper_rad_s": self.continuum_upper.tolist(),
                                "lower_rel_dev": [nan(r) for r in lo_rel], "upper_rel_dev": [nan(r) for r in hi_rel],
                                "observed_order_r1": [nan(r) for r in self.observed_order]},
                # the modal JSON keys for the drive's own discrete model
                "omega_rad_s": nan(np.sort(np.concatenate(self.rows["discrete"]))),
                "representation": "comparison"}

    def table(self) -> str:
        R = self.R
        lines = [self.description, "",
                 f"branch roots [rad/s]: p_r1 (lower, mechanisms in phase, below k) and p_r2 (upper, antiphase), r = 1..{R}"]
        hdr = f"{'representation':<34}" + "".join(f" {'p_%d1' % (r + 1):>12}" for r in range(R)) + \
              "".join(f" {'p_%d2' % (r + 1):>12}" for r in range(R))
        lines.append(hdr)
        for name, (lo, hi) in self.rows.items():
            lines.append(f"{name:<34}" + "".join(f" {v:>12.7g}" for v in lo) + "".join(f" {v:>12.7g}" for v in hi))
        lines += ["", f"convergence of the discrete model to the pseudo-medium ({self.convergence_source}); "
                      "totals (n m, k, shaft) fixed",
                  f"{'n':>6} {'p_11':>12} {'rel.dev':>10} {'p_12':>12} {'rel.dev':>10} {'order(p11)':>10} {'order(p12)':>10}"]
        lo_rel, hi_rel = self.convergence_rel
        order = self.observed_order
        for i, n in enumerate(self.convergence_n):
            o = ("", "") if i == 0 else tuple(f"{v:.3f}" for v in order[i - 1])
            lines.append(f"{n:>6d} {self.convergence_lower[i, 0]:>12.7g} {lo_rel[i, 0]:>10.2e} "
                         f"{self.convergence_upper[i, 0]:>12.7g} {hi_rel[i, 0]:>10.2e} {o[0]:>10} {o[1]:>10}")
        lines.append(f"{'n→∞':>6} {self.continuum_lower[0]:>12.7g} {'':>10} {self.continuum_upper[0]:>12.7g}   (10.50)")
        return "\n".join(lines)


def compare_model(model: DriveModel, *, R: int = 3, convergence_n=None) -> DriveComparison:
    R = int(min(R, model.n))
    rows = {}
    for rep in ("discrete", "transfer-matrix", "continuum"):
        rows[rep] = branch_roots(model, rep, R)
    reg = regular_of(model)
    if reg is not None and reg.output == "free":
        allf = reg.natural_frequencies()
        rows["closed form (10.36)+(10.16)"] = _branches(allf, model.mechanism.k, R)
    free = model.boundary == "free-free"
    c_lo, c_hi = continuum_roots(model, R + free)
    if free:         # its rigid-body root 0 is no branch root of the other representations (_branches drops it)
        c_lo, c_hi = c_lo[c_lo > 0][:R], c_hi[:R]
    rows["pseudo-medium (10.50)"] = (c_lo, c_hi)
    if convergence_n is None:
        convergence_n = [model.n * 2**i for i in range(5)]
    ns = np.array(sorted({int(v) for v in convergence_n}))
    lows, highs = [], []
    src = "discrete FE/lumped model (sparse modal analysis)"
    for n in ns:
        m_n = model.with_n(int(n))
        lo, hi = branch_roots(m_n, "discrete", 1)
        lows.append(lo), highs.append(hi)
    return DriveComparison(description=model.describe(), R=R, rows=rows, convergence_n=ns,
                           convergence_lower=np.array(lows), convergence_upper=np.array(highs),
                           continuum_lower=c_lo[:1], continuum_upper=c_hi[:1], convergence_source=src)


# ------------------------------------------------------------------ spectrum vs n
@dataclass
class SpectrumSweep:
    """All natural frequencies of the drive for n = 1..N (totals fixed), with the pass bands
    |xi(p)| <= 1 of the block, the stop band of J*(p) and the continuum limit."""

    n: np.ndarray
    roots: list                      # per n: all 2n natural frequencies (rad/s)
    lower_band: np.ndarray           # (len(n), 2) pass band |xi| <= 1 below k
    upper_band: np.ndarray           # (len(n), 2) pass band above p_*
    stop_band: tuple
    continuum_lower: np.ndarray      # (10.50) lower roots r = 1..R
    continuum_upper: np.ndarray
    k: float
    description: str = ""

    def to_dict(self) -> dict:
        return {"n": self.n.tolist(), "roots_rad_s": [r.tolist() for r in self.roots],
                "lower_band_rad_s": self.lower_band.tolist(), "upper_band_rad_s": self.upper_band.tolist(),
                "stop_band_rad_s": list(self.stop_band), "continuum_lower_rad_s": self.continuum_lower.tolist(),
                "continuum_upper_rad_s": self.continuum_upper.tolist(), "k_rad_s": self.k}


def spectrum_sweep(model: DriveModel, n_values, R: int = 4) -> SpectrumSweep:
    """Spectra of ``model.with_n(n)`` (lumped shaft: closed forms (10.36), verified against the
    transfer-matrix count) for every n in ``n_values``."""
    from discrete.transfer import count_below

    if regular_of(model) is None:
        raise ModelError("[drive.shaft]", "type", "distributed", "'lumped' for the spectrum-vs-n sweep")
    ns = np.array(sorted({int(v) for v in n_values}))
    roots, lo_b, hi_b = [], [], []
    for n in ns:
        m_n = model.with_n(int(n))
        reg = regular_of(m_n)
        w = reg.natural_frequencies()
        chain, _, _ = build_chain(m_n)
        top = w.max() * (1 + 1e-9)
        if int(count_below(chain, top)[0]) != w.size:
            raise ModelError("spectrum_sweep", "n", int(n), "a drive whose closed form and TM count agree")
        roots.append(w)
        lo, hi = reg.pass_bands()
        lo_b.append(lo)
        hi_b.append(hi)
    s = model.smeared()
    c_lo, c_hi = continuum_roots(model, R)
    return SpectrumSweep(n=ns, roots=roots, lower_band=np.array(lo_b), upper_band=np.array(hi_b),
                         stop_band=stop_band(s["rho"], s["m_bar"], s["k"], s["ratio"]), continuum_lower=c_lo,
                         continuum_upper=c_hi, k=s["k"], description=model.describe())
