"""Identify 3D shaft modes as bending, torsion or axial.

Each mode's displacement at the vertices is fitted, slice by slice along x, with the rigid
motion of a cross-section, u = a + w x r (translation a, rotation w); the kinetic-energy
shares of the section motions then classify the mode:

* axial:   m a_x^2                (sections translate along the axis)
* bending: m (a_y^2 + a_z^2)      (sections translate sideways)
* torsion: J_p w_x^2              (sections turn about the axis)

with m and J_p the mass and polar inertia of the slice's nodes (lumped, equal weights per
vertex of the slice).  A share above ``threshold`` names the mode; otherwise it is
"mixed" (e.g. cross-section breathing modes, high modes of stubby shafts).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from discrete.linear.modal import ModalResult, modal_analysis

KINDS = ("bending", "torsion", "axial")


@dataclass
class SolidModalResult(ModalResult):
    """A :class:`ModalResult` plus the kind of each mode and its energy shares
    (columns: bending, torsion, axial)."""

    kinds: list = field(default_factory=list)
    shares: np.ndarray | None = None

    def to_dict(self) -> dict:
        d = super().to_dict()
        d["kinds"] = list(self.kinds)
        d["shares"] = {k: self.shares[:, i].tolist() for i, k in enumerate(KINDS)} if self.shares is not None else {}
        return d


def section_shares(points: np.ndarray, disp: np.ndarray, n_slices: int | None = None) -> np.ndarray:
    """Energy shares (bending, torsion, axial) of one displacement field (n_points, 3)."""
    x = points[:, 0]
    xs = np.unique(np.round(x / (np.ptp(x) or 1.0), 9))
    if n_slices is None and xs.size <= 400:
        keys = np.round(x / (np.ptp(x) or 1.0), 9)
        groups = [np.flatnonzero(keys == k) for k in xs]
    else:                               # unstructured (imported) meshes: bins along x
        nb = n_slices or 40
        edges = np.linspace(x.min(), x.max() + 1e-12 * (np.ptp(x) or 1.0), nb + 1)
        idx = np.clip(np.searchsorted(edges, x, side="right") - 1, 0, nb - 1)
        groups = [np.flatnonzero(idx == b) for b in range(nb)]
    e = np.zeros(3)
    total = 0.0
    for g in groups:
        if g.size < 4:
            continue
        p = points[g] - np.array([0.0, 0.0, 0.0])
        y, z = p[:, 1], p[:, 2]
        u = disp[g]
        # rigid section motion: u = a + w x (0, y, z) -> columns for a_x, a_y, a_z, w_x, w_y, w_z
        n = g.size
        A = np.zeros((3 * n, 6))
        A[0::3, 0] = 1
        A[1::3, 1] = 1
        A[2::3, 2] = 1
        A[1::3, 3], A[2::3, 3] = -z, y                # w_x: (0, -z, y)
        A[0::3, 4] = z                                 # w_y: (z, 0, -x~0)
        A[0::3, 5] = -y                                # w_z: (-y, x~0, 0)
        coef, *_ = np.linalg.lstsq(A, u.ravel(), rcond=None)
        m = float(n)
        Jp = float(np.sum(y * y + z * z))
        e += [m * (coef[1] ** 2 + coef[2] ** 2), Jp * coef[3] ** 2, m * coef[0] ** 2]
        total += float(np.sum(u * u))
    return e / total if total > 0 else e


def classify(points: np.ndarray, shapes_at_points: list[np.ndarray], threshold: float = 0.6):
    """(kinds, shares) for a list of (n_points, 3) displacement fields."""
    shares = np.array([section_shares(points, d) for d in shapes_at_points])
    kinds = [KINDS[int(np.argmax(s))] if s.max() >= threshold else "mixed" for s in shares]
    return kinds, shares


def solid_modal(solid, n_modes: int = 10, **kw) -> SolidModalResult:
    """Lowest ``n_modes`` modes of a 3D solid model (sparse shift-invert), classified."""
    res = modal_analysis(solid.system, n_modes, **kw)
    pts = solid.vertices
    kinds, shares = classify(pts, [solid.displacement_field(res.shapes[:, r]) for r in range(res.shapes.shape[1])])
    kinds = ["rigid" if rg else k for k, rg in zip(kinds, res.rigid)]
    return SolidModalResult(**vars(res), kinds=kinds, shares=shares)
