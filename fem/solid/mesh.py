"""Hexahedral meshes of (stepped, optionally hollow) circular shafts along x.

The cross-section is an O-grid: a square core, a transition ring blending the square into
the first circle, and polar rings out to every segment radius (inner radii of tubes are
rings too), so every segment uses the same 2D topology restricted to its own annulus and
neighbouring segments share their interface nodes.  The mesh is made quadratic
(:class:`skfem.MeshHex2`) with the mid-nodes on arcs moved onto the true circles, so the
geometry error of the polygonal section (about (2 pi/N)^2/6 in area) disappears.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from discrete.errors import ModelError


@dataclass
class ShaftMeshSpec:
    """Mesh density: ``n_quarter`` divisions of each quarter circle (N = 4 n_quarter around),
    ``radial`` element layers per ring, ``axial``: elements per metre of length or None to
    use each segment's ``elements`` count from the model."""

    n_quarter: int = 3
    radial: int = 1
    axial_per_segment: list[int] | None = None

    def __post_init__(self):
        if isinstance(self.n_quarter, bool) or not isinstance(self.n_quarter, int) or self.n_quarter < 1:
            raise ModelError("solid mesh", "n_quarter", self.n_quarter, "an integer >= 1")
        if isinstance(self.radial, bool) or not isinstance(self.radial, int) or self.radial < 1:
            raise ModelError("solid mesh", "radial", self.radial, "an integer >= 1")


def _section_2d(radii: np.ndarray, n: int, radial: int):
    """2D O-grid of the disc of radius max(radii) with rings at every radius in ``radii``.

    Returns nodes (P, 2), quads (Q, 4) counter-clockwise in (y, z), and the outer radius of the ring
    each quad belongs to (the core and transition quads report radii[0])."""
    r0 = radii[0]
    a = 0.5 * r0                                    # half width of the core square
    N = 4 * n
    # core square (n+1) x (n+1) nodes, index core[i, j]
    g = np.linspace(-a, a, n + 1)
    X, Y = np.meshgrid(g, g, indexing="ij")
    nodes = [np.column_stack([X.ravel(), Y.ravel()])]
    core = np.arange((n + 1) ** 2).reshape(n + 1, n + 1)
    quads, owner = [], []
    for i in range(n):
        for j in range(n):
            quads.append([core[i, j], core[i + 1, j], core[i + 1, j + 1], core[i, j + 1]])
            owner.append(r0)
    # boundary of the square, counter-clockwise from the corner (a, -a)... as N points
    bnd = []
    for k in range(n):            # right edge, bottom to top
        bnd.append(core[n, k])
    for k in range(n):            # top edge, right to left
        bnd.append(core[n - k, n])
    for k in range(n):            # left edge, top to bottom
        bnd.append(core[0, n - k])
    for k in range(n):            # bottom edge, left to right
        bnd.append(core[k, 0])
    bnd = np.array(bnd)
    sq = nodes[0][bnd]
    theta = np.arctan2(sq[:, 1], sq[:, 0])
    theta = np.where(theta < theta[0] - 1e-12, theta + 2 * np.pi, theta)
    # angles on the circle: equal spacing, starting at the corner direction of bnd[0]
    phi = theta[0] + 2 * np.pi * np.arange(N) / N
    count = nodes[0].shape[0]
    prev = bnd
    m = max(2, radial)
    layers = [(s, None) for s in np.arange(1, m + 1) / m]          # transition to r0
    for k in range(1, radii.size):
        for s in np.arange(1, radial + 1) / radial:
            layers.append((s, k))
    for s, k in layers:
        if k is None:
            circ = r0 * np.column_stack([np.cos(phi), np.sin(phi)])
            pts = (1 - s) * sq + s * circ
            own = r0
        else:
            rr = radii[k - 1] + s * (radii[k] - radii[k - 1])
            pts = rr * np.column_stack([np.cos(phi), np.sin(phi)])
            own = radii[k]
        idx = count + np.arange(N)
        count += N
        nodes.append(pts)
        for q in range(N):
            q1 = (q + 1) % N
            quads.append([prev[q], idx[q], idx[q1], prev[q1]])      # counter-clockwise like the core
            owner.append(own)
        prev = idx
    return np.vstack(nodes), np.asarray(quads), np.asarray(owner), r0, N


def stepped_shaft_hex(xs, layer_segment, outer, inner, n_quarter: int = 3, radial: int = 1):
    """A :class:`skfem.MeshHex2` of consecutive cylinders along x.

    ``xs``: the layer coordinates (increasing), ``layer_segment``: the segment index of each
    layer (len(xs) - 1), ``outer``/``inner`` radii per segment (inner 0 for solid).
    Returns (mesh, segment index per element)."""
    from skfem import MeshHex1, MeshHex2

    xs, outer, inner = (np.asarray(v, float) for v in (xs, outer, inner))
    layer_segment = np.asarray(layer_segment, dtype=int)
    rings = np.unique(np.concatenate([outer, inner[inner > 0]]))
    if np.any(inner > 0) and inner[inner > 0].min() != rings[0]:
        raise ModelError("solid mesh", "di", 2 * inner[inner > 0].min(),
                         "a bore no larger than the smallest outer diameter")
    p2, q2, own, r0, N = _section_2d(rings, n_quarter, radial)
    P = p2.shape[0]
    hexes, seg = [], []
    for lay, k in enumerate(layer_segment):
        keep = own <= outer[k] * (1 + 1e-12)
        if inner[k] > 0:
            keep &= own > inner[k] * (1 + 1e-12)
        for q in q2[keep]:
            b, t = q + lay * P, q + (lay + 1) * P
            # skfem's reference vertices (ElementHex1.doflocs): (1,1,1), (1,1,0), (1,0,1), (0,1,1),
            # (1,0,0), (0,1,0), (0,0,1), (0,0,0) in local axes (a: quad edge 0->1, b: quad
            # edge 0->3, c: along x; b = this layer, t = the next one)
            hexes.append([t[2], b[2], t[1], t[3], b[1], b[3], t[0], b[0]])
            seg.append(k)
    hexes = np.asarray(hexes).T
    pts3 = np.column_stack([np.repeat(xs, P), np.tile(p2[:, 0], xs.size), np.tile(p2[:, 1], xs.size)])
    used = np.unique(hexes)
    remap = -np.ones(pts3.shape[0], dtype=int)
    remap[used] = np.arange(used.size)
    m1 = MeshHex1(np.ascontiguousarray(pts3[used].T), np.ascontiguousarray(remap[hexes].astype(np.int64)))
    m2 = MeshHex2.from_mesh(m1)
    _snap_to_circles(m2, rings, r0, N)
    return m2, np.asarray(seg)


def _snap_to_circles(mesh, rings: np.ndarray, r0: float, N: int) -> None:
    """Move quadratic nodes of the polar rings onto the true circles: a Cartesian midpoint
    between two nodes at radius R that are 2 pi/N apart lies at R cos(pi/N)."""
    d = mesh.doflocs
    r = np.hypot(d[1], d[2])
    c = math.cos(math.pi / N)
    outer_zone = r >= r0 * c * (1 - 1e-9)
    ang = np.arctan2(d[2], d[1])
    step = 2 * math.pi / N
    # ring nodes sit at offset + k step; the offset is read from the outermost circle
    vert = mesh.p
    rv = np.hypot(vert[1], vert[2])
    on = np.isclose(rv, rings[-1], rtol=1e-9)
    off = np.arctan2(vert[2, on], vert[1, on])[0] if on.any() else 0.0
    frac = np.mod((ang - off) / step, 1.0)
    mid = np.isclose(frac, 0.5, atol=1e-6)
    fix = outer_zone & mid
    d[1, fix] /= c
    d[2, fix] /= c
