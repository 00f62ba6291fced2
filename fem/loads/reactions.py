"""Support and bearing reactions of FE models and rotors: the force (moment) each support exerts on
the structure.

* Constrained DOFs (clamped/pinned supports, rigid rotor supports, drivers): R_b = (M q'' + C q' +
  K q (+ i H q))_b - F_b, the row of the equations of motion that the constraint closes.  Harmonic
  responses go through :func:`discrete.linear.reactions.constraint_reactions` (the same dynamic
  stiffness and damping options as the harmonic analysis).
* Spring supports and springs to ground of point attachments: -k q (and -k_r theta), with the
  complex factor (1 + 2 i delta) of a global hysteretic psi and beta k q' of Rayleigh damping.
* Rotor bearings: f = -K_b d - C_b d' with d the shaft's (v, w) relative to its pedestal (or the
  ground), the coefficients at the spin speed; pedestals: -k q_p - c q_p' from the ground.

With the section loads this closes the balance: the reactions plus the applied loads equal the
inertia (and damping-to-ground) forces of the whole structure, to round-off (validation ``loads-*``).
"""
from __future__ import annotations

import numpy as np

from discrete.errors import ModelError

from .motion import WHERE, ElementDamping, motion


def _force(n: int, force, t: int) -> np.ndarray:
    if force is None:
        return np.zeros((n, t))
    F = np.asarray(force)
    if F.dtype.kind not in "iufc" or F.shape[0] != n or F.ndim not in (1, 2) or not np.all(np.isfinite(F)):
        raise ModelError(WHERE, "force", f"shape {F.shape}", f"a finite load vector of {n} entries (or ({n}, n_t))")
    return F[:, None] if F.ndim == 1 else F


def _out(values: np.ndarray, single: bool) -> np.ndarray:
    return np.asarray(values[0]) if single else values


def support_reactions(fe_model, q, *, qd=None, qdd=None, omega=None, eigenvalue=None, force=None,
                      damping=None, speed=None) -> dict[str, np.ndarray]:
    """{support: reaction} for the state ``q`` (as :func:`~fem.loads.section_loads`) under the applied
    nodal loads ``force`` (n_dofs,) or (n_dofs, n_t).  Keys: the DOF label of every constrained DOF
    (``"w@x=0"``) and ``"spring:<label>"`` for springs to ground; rotors: see :func:`rotor_reactions`.
    Values are the force (N) or moment (N m) on the structure, (n_t,) or one number for one state."""
    from ..rotor.assembly import RotorSystem

    if isinstance(fe_model, RotorSystem):
        return rotor_reactions(fe_model, q, qd=qd, qdd=qdd, omega=omega, eigenvalue=eigenvalue, force=force,
                               speed=speed)
    system = fe_model.system
    mo = motion(system.n_dofs, q, qd, qdd, omega, eigenvalue)
    t = mo.q.shape[1]
    F = _force(system.n_dofs, force, t)
    b = system.constrained
    dmp = ElementDamping.of(damping)
    out = {}
    if mo.kind == "harmonic":
        from discrete.linear.reactions import constraint_reactions
        from discrete.linear import Damping

        if F.shape[1] not in (1, t):
            raise ModelError(WHERE, "force", f"shape {F.shape}", "one load vector, or one per frequency")
        use = damping if damping is None or damping.type != "modal" else Damping(type="viscous")
        R = np.zeros((b.size, t), dtype=complex)
        for j in range(t) if F.shape[1] > 1 else [None]:
            cols = slice(None) if j is None else slice(j, j + 1)
            rr = constraint_reactions(system, mo.parameter[cols], mo.q[:, cols].T,
                                      force=F[:, 0 if j is None else j], damping=use)
            R[:, cols] = rr.values.T
    else:
        C = system.C + dmp.alpha * system.M + dmp.beta * system.K
        R = (system.K @ mo.q + C @ mo.qd + system.M @ mo.qdd)[b] - F[b]
    for k, i in enumerate(b):
        out[system.label(int(i))] = _out(R[k], mo.single)
    springs = spring_stiffness(fe_model)
    factor = (1.0 + 1j * dmp.added_loss) if mo.kind == "harmonic" else 1.0
    for i, k in springs.items():
        if i not in set(b.tolist()):
            val = -(factor * k * mo.q[i] + dmp.beta * k * mo.qd[i])
            out["spring:" + system.label(i)] = _out(val, mo.single)
    return out


def spring_stiffness(fe_model) -> dict[int, float]:
    """{DOF: stiffness} of the springs to ground of a shaft model (spring supports, point springs)."""
    model, system = fe_model.model, fe_model.system
    primary = model.fields[0]
    rotation = model.fields[1] if len(model.fields) > 1 else None
    out: dict[int, float] = {}
    items = [(s.x, s.k, s.kr) for s in model.supports if s.type == "spring"] + [(p.x, p.k, p.kr) for p in model.points]
    for x, k, kr in items:
        for fld, val in ((primary, k), (rotation, kr)):
            if fld is not None and val:
                i = system.dof_index(field=fld, x=x)
                out[i] = out.get(i, 0.0) + val
    return out


def _bearing_coefficients(rs, speeds: np.ndarray) -> list[np.ndarray]:
    """(n_t, 8) coefficients (kyy, kyz, kzy, kzz, cyy, cyz, czy, czz) of every bearing at the speeds."""
    from ..rotor.model import BEARING_COEFFICIENTS

    tables = {t.index: t for t in rs.tables}
    out = []
    for b_no, b in enumerate(rs.rotor.bearings, 1):
        if b_no in tables:
            out.append(tables[b_no].at(speeds))
        else:
            tab = b.table()
            out.append(np.tile([tab[k][0] for k in BEARING_COEFFICIENTS], (speeds.size, 1)))
    return out


def rotor_reactions(rs, q, *, qd=None, qdd=None, omega=None, eigenvalue=None, force=None, speed=None) -> dict:
    """Reactions of a rotor (:class:`~fem.rotor.RotorSystem`) at the spin ``speed`` (rad/s; default:
    ``omega``, the synchronous response, else 0).  Keys: ``"<bearing name, or bearing <number>>@x=<x>:F_y"`` (and
    ``F_z``, ``F_x`` for a thrust bearing) -- the bearing's force on the shaft --, ``"pedestal
    <name>:F_y"``/``F_z`` -- the ground's force on the pedestal --, and the DOF label of every rigidly
    supported DOF (``"v@x=0"``).  Values as :func:`support_reactions`."""
    mo = motion(rs.n_dofs, q, qd, qdd, omega, eigenvalue)
    t = mo.q.shape[1]
    if speed is None:
        speed = mo.parameter.real if mo.kind == "harmonic" else 0.0
    spin = np.broadcast_to(np.asarray(speed, dtype=float), (t,))
    F = _force(rs.n_dofs, force, t)
    out = {}
    nd = rs.node_dofs
    n_shaft = rs.node_x.size * len(rs.fields)
    forces = bearing_forces(rs, spin, lambda idx: mo.q[idx].T, lambda idx: mo.qd[idx].T)
    for b_no, b in enumerate(rs.rotor.bearings, 1):
        fy, fz = forces[b_no - 1]
        name = f"{b.name or f'bearing {b_no}'}@x={b.x:g}"
        out[name + ":F_y"], out[name + ":F_z"] = _out(fy, mo.single), _out(fz, mo.single)
        if "u" in nd and (b.k_axial or b.c_axial):
            iu = nd["u"][rs.node(b.x)]
            out[name + ":F_x"] = _out(-(b.k_axial * mo.q[iu] + b.c_axial * mo.qd[iu]), mo.single)
    for i, p in enumerate(rs.rotor.pedestals):
        iv, iw = n_shaft + 2 * i, n_shaft + 2 * i + 1
        out[f"pedestal {p.name}:F_y"] = _out(-(p.kyy * mo.q[iv] + p.cyy * mo.qd[iv]), mo.single)
        out[f"pedestal {p.name}:F_z"] = _out(-(p.kzz * mo.q[iw] + p.czz * mo.qd[iw]), mo.single)
    b_idx = rs.constrained
    if b_idx.size:
        K, C = rs.stiffness(float(spin[0])), rs.damping(float(spin[0]))
        if rs.speed_dependent and np.any(spin != spin[0]):
            R = np.stack([(rs.stiffness(s) @ mo.q[:, j] + (rs.damping(s) + s * rs.G) @ mo.qd[:, j]
                           + rs.M @ mo.qdd[:, j]) for j, s in enumerate(spin)], axis=1)
        else:
            R = K @ mo.q + C @ mo.qd + (rs.G @ mo.qd) * spin + rs.M @ mo.qdd
        R = R[b_idx] - F[b_idx]
        for k, i in enumerate(b_idx):
            out[f"{rs.dof_field[i]}@x={rs.dof_x[i]:.6g}"] = _out(R[k], mo.single)
    return out


def bearing_forces(rs, speeds, disp, vel=None, linear_only: bool = False) -> dict[int, tuple]:
    """{bearing index: (F_y, F_z)} -- the force of every linear bearing (or seal) on the shaft,
    f = -K(Omega) d - C(Omega) d' with d the shaft node's (v, w) relative to its pedestal (or the ground)
    and the coefficients of the assembly's tables at each speed.  ``disp(dofs)`` gives those DOFs'
    displacements at the samples ((n_samples, len(dofs)): real, or complex amplitudes), ``vel(dofs)``
    their rates (None: i Omega times the displacements, a synchronous response); ``speeds`` (n_samples,)
    rad/s.  ``linear_only``: leave out the bearings that run with their own nonlinear law (run-ups)."""
    speeds = np.atleast_1d(np.asarray(speeds, dtype=float))
    ped = {p.name: i for i, p in enumerate(rs.rotor.pedestals)}
    n_shaft = rs.node_x.size * len(rs.fields)
    coeffs = _bearing_coefficients(rs, speeds)
    out = {}
    for k, (b, c) in enumerate(zip(rs.rotor.bearings, coeffs)):
        if linear_only and getattr(b, "nonlinear", False):
            continue
        node = rs.node(b.x)
        idx = [int(rs.node_dofs["v"][node]), int(rs.node_dofs["w"][node])]
        if b.pedestal is not None:
            p = n_shaft + 2 * ped[b.pedestal]
            idx += [p, p + 1]
        q = np.asarray(disp(idx))
        qd = 1j * speeds[:, None] * q if vel is None else np.asarray(vel(idx))
        d, dd = q[:, :2].T, qd[:, :2].T
        if b.pedestal is not None:
            d, dd = d - q[:, 2:].T, dd - qd[:, 2:].T
        n_t = d.shape[1]
        Kb = c[:, :4].T.reshape(2, 2, n_t)
        Cb = c[:, 4:].T.reshape(2, 2, n_t)
        f = -(np.einsum("abt,bt->at", Kb, d) + np.einsum("abt,bt->at", Cb, dd))
        out[k] = (f[0], f[1])
    return out
