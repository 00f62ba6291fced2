"""Description of a rotor: shaft segments, discs, bearings and seals, pedestals, couplings, rigid supports.

Axes: x along the shaft (spin axis, the rotor spins about +x at the speed Omega > 0), y and z
lateral.  DOFs per node: v (along y), w (along z), theta_y, theta_z (rotations about y and z;
theta_z = dv/dx and theta_y = -dw/dx for a slender shaft), and with ``dofs = "full"`` also u
(axial, along x) and theta_x (torsion).  SI units: m, kg, N, s, rad; speeds are rad/s.

Every value is checked here, in ``__post_init__`` of each dataclass (own values) and of
:class:`Rotor` (positions along the shaft, names), so the Python API and a model file that
maps onto these dataclasses field for field give the same messages.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Sequence

import numpy as np

from discrete import checks
from discrete.errors import ModelError

from ..sections import Material

DOF_SETS = {"lateral": ("v", "w", "theta_y", "theta_z"),
            "full": ("u", "v", "w", "theta_x", "theta_y", "theta_z")}
LATERAL = ("v", "w", "theta_y", "theta_z")
#: the eight linear bearing coefficients: force on the shaft f = -K d - C d' with d = (v, w) (relative
#: to the pedestal when there is one), K = [[kyy, kyz], [kzy, kzz]], C = [[cyy, cyz], [czy, czz]]
BEARING_COEFFICIENTS = ("kyy", "kyz", "kzy", "kzz", "cyy", "cyz", "czy", "czz")
#: linear; pchip (shape-preserving cubic, Fritsch-Carlson); spline (cubic spline through the points,
#: not-a-knot ends); smoothing-spline (ROSS's convention: scipy's UnivariateSpline, a cubic smoothing
#: spline with s = number of points -- not an interpolant, it misses the table's points)
INTERPOLATIONS = ("linear", "pchip", "spline", "smoothing-spline")
#: a speed outside a table: refuse (an error), hold (the end value), linear (the tangent line of the
#: interpolant at the table's end: for linear interpolation the end segment's line), continue (the
#: interpolant's end pieces continued: for smoothing-spline ROSS's extrapolation)
EXTRAPOLATIONS = ("refuse", "hold", "linear", "continue")


def _finite(value, key: str, where: str, *, minimum: float | None = None, strict: bool = False) -> float:
    v = checks.number(where, key, value, "a finite number")      # a bool or a string is never a number
    if minimum is not None and (v < minimum or (strict and v == minimum)):
        raise ModelError(where, key, value, f"a number {'>' if strict else '>='} {minimum:g}")
    return v


def _check_material(mat: Material, where: str) -> None:
    if not isinstance(mat, Material):
        raise ModelError(where, "material", mat, "a fem.sections.Material(E, G, rho)")
    _finite(mat.E, "E", where + " material", minimum=0.0, strict=True)
    _finite(mat.G, "G", where + " material", minimum=0.0, strict=True)
    # rho = 0 is the massless shaft of the Jeffcott idealisation (all inertia in the discs)
    _finite(mat.rho, "rho", where + " material", minimum=0.0)


@dataclass
class Layer:
    """A further concentric layer of a shaft segment (a sleeve, an impeller hub, a shrink fit).

    Annulus of outer diameter ``d`` and bore ``di`` at the segment's start, ``d_end``/``di_end`` at
    its end (None: uniform), its own ``material`` and ``shear_coefficient`` (None: Cowper's for its
    own annulus).  ROSS's convention (shaft elements that share a node number are summed): each
    layer is a Timoshenko element of its own on the segment's nodes, with its own shear parameter
    Phi = 12 E I / (kappa G A L^2) and its own interpolation; the matrices of the layers are added.
    ``mass_only``: the layer adds inertia only -- translation rho A, rotary rho I, polar rho I_p
    (gyroscopic and, with ``dofs = "full"``, axial and torsional inertia) -- and no stiffness; its
    interpolation still uses its own Phi from its material's E and G."""

    d: float
    di: float
    material: Material
    d_end: float | None = None
    di_end: float | None = None
    shear_coefficient: float | None = None
    mass_only: bool = False

    def check(self, where: str) -> None:
        _finite(self.d, "d", where, minimum=0.0, strict=True)
        if self.d_end is not None:
            _finite(self.d_end, "d_end", where, minimum=0.0, strict=True)
        _finite(self.di, "di", where, minimum=0.0)
        if self.di_end is not None:
            _finite(self.di_end, "di_end", where, minimum=0.0)
        if not self.di < self.d:
            raise ModelError(where, "di", self.di, f"a bore smaller than the outer diameter d = {self.d:g} m")
        if not self.bore_end < self.outer_end:
            raise ModelError(where, "di_end", self.bore_end,
                             f"a bore smaller than the outer diameter at the end ({self.outer_end:g} m)")
        _check_material(self.material, where)
        _check_kappa(self.shear_coefficient, where)
        if not isinstance(self.mass_only, (bool, np.bool_)):
            raise ModelError(where, "mass_only", self.mass_only, "true or false")

    @property
    def outer_end(self) -> float:
        return self.d if self.d_end is None else float(self.d_end)

    @property
    def bore_end(self) -> float:
        return self.di if self.di_end is None else float(self.di_end)


def _check_kappa(kappa, where: str) -> None:
    if kappa is not None:
        k = _finite(kappa, "shear_coefficient", where, minimum=0.0, strict=True)
        if k > 1.5:
            raise ModelError(where, "shear_coefficient", k, "a shear coefficient in (0, 1.5] (about 0.85-0.9 "
                             "for solid shafts)")


def _overlap(a, b) -> bool:
    """Whether two annuli (d, di, d_end, di_end) share area at the start or the end (1e-12 slack)."""
    (d0, i0, d1, i1), (e0, j0, e1, j1) = a, b
    tol = 1e-12 * max(d0, d1, e0, e1)
    return (min(d0, e0) - max(i0, j0) > tol) or (min(d1, e1) - max(i1, j1) > tol)


@dataclass
class ShaftSegment:
    """A piece of shaft; segments are consecutive along x from x = 0.

    ``length`` (m) divided into ``elements`` equal Timoshenko elements; outer diameter ``d`` (m)
    at the start and ``d_end`` at the end (None: uniform; otherwise a linear taper), bore ``di``
    and ``di_end`` likewise (0: solid); ``material`` (E, G in Pa, rho in kg/m^3; rho = 0 allowed
    for a massless shaft); ``shear_coefficient`` kappa (None: Cowper's value for the hollow
    circle, 6 (1 + nu)(1 + m^2)^2 / ((7 + 6 nu)(1 + m^2)^2 + (20 + 12 nu) m^2), m = di/d);
    ``added_mass_per_length`` (kg/m): non-structural mass carried by the segment (translational
    inertia only, e.g. windings or sleeves that add no stiffness); ``layers``: further concentric
    :class:`Layer` s on the same nodes (a layered section: each layer its own Timoshenko element,
    mass-only layers with translational, rotary and polar inertia and no stiffness).  The
    segment's own (d, di, material) is the innermost structural layer; layers must not overlap."""

    length: float
    elements: int
    d: float
    material: Material
    d_end: float | None = None
    di: float = 0.0
    di_end: float | None = None
    shear_coefficient: float | None = None
    added_mass_per_length: float = 0.0
    layers: Sequence[Layer] = ()

    def check(self, where: str) -> None:
        _finite(self.length, "length", where, minimum=0.0, strict=True)
        if isinstance(self.elements, bool) or not isinstance(self.elements, (int, np.integer)) or self.elements < 1:
            raise ModelError(where, "elements", self.elements, "an integer >= 1")
        _finite(self.d, "d", where, minimum=0.0, strict=True)
        if self.d_end is not None:
            _finite(self.d_end, "d_end", where, minimum=0.0, strict=True)
        _finite(self.di, "di", where, minimum=0.0)
        if self.di_end is not None:
            _finite(self.di_end, "di_end", where, minimum=0.0)
        if not self.di < self.d:
            raise ModelError(where, "di", self.di, f"a bore smaller than the outer diameter d = {self.d:g} m")
        if not self.bore_end < self.outer_end:
            raise ModelError(where, "di_end", self.bore_end,
                             f"a bore smaller than the outer diameter at the end ({self.outer_end:g} m)")
        _check_material(self.material, where)
        _check_kappa(self.shear_coefficient, where)
        _finite(self.added_mass_per_length, "added_mass_per_length", where, minimum=0.0)
        if isinstance(self.layers, (str, bytes)) or not isinstance(self.layers, Sequence):
            raise ModelError(where, "layer", self.layers, "a list of fem.rotor.Layer")
        rings = [(self.d, self.di, self.outer_end, self.bore_end)]
        for j, lay in enumerate(self.layers, 1):
            w = f"{where} layer #{j}"
            if not isinstance(lay, Layer):
                raise ModelError(w, "layer", lay, "a fem.rotor.Layer(d, di, material, ...)")
            lay.check(w)
            ring = (lay.d, lay.di, lay.outer_end, lay.bore_end)
            for k, other in enumerate(rings):
                if _overlap(ring, other):
                    raise ModelError(w, "di", lay.di, "a layer that does not overlap "
                                     + ("the segment's own section" if k == 0 else f"layer #{k}")
                                     + f" (d = {other[0]:g}, di = {other[1]:g} m): concentric layers share no area")
            rings.append(ring)

    @property
    def outer_end(self) -> float:
        return self.d if self.d_end is None else float(self.d_end)

    @property
    def bore_end(self) -> float:
        return self.di if self.di_end is None else float(self.di_end)

    def outer_diameter(self, u: float) -> float:
        """The largest outer diameter over the segment's own section and its layers at the
        fraction ``u`` in [0, 1] of its length, m."""
        return max(d0 + (d1 - d0) * u for d0, d1 in
                   [(self.d, self.outer_end)] + [(lay.d, lay.outer_end) for lay in self.layers])


@dataclass
class Disc:
    """A rigid disc (or any lumped mass with inertia) at ``x`` (m): ``mass`` (kg), diametral
    moment of inertia ``Id`` and polar moment ``Ip`` (kg m^2) about its centre on the shaft axis.
    ``Ip`` gives the gyroscopic moments Ip Omega (theta_z', -theta_y') and, with ``dofs =
    "full"``, the torsional inertia."""

    x: float
    mass: float
    Id: float = 0.0
    Ip: float = 0.0
    name: str = ""

    @classmethod
    def from_geometry(cls, x: float, width: float, d: float, di: float, rho: float, name: str = "") -> "Disc":
        """A uniform annular disc of axial ``width``, outer diameter ``d``, bore ``di`` (m) and
        density ``rho``: m = rho pi (d^2 - di^2) width / 4, Ip = m (d^2 + di^2) / 8,
        Id = Ip / 2 + m width^2 / 12."""
        where = f"disc {name or x!r} geometry"
        for key, val in (("width", width), ("d", d), ("rho", rho)):
            _finite(val, key, where, minimum=0.0, strict=True)
        _finite(di, "di", where, minimum=0.0)
        if not di < d:
            raise ModelError(where, "di", di, f"a bore smaller than d = {d:g} m")
        m = rho * math.pi * (d * d - di * di) * width / 4.0
        Ip = m * (d * d + di * di) / 8.0
        return cls(x=x, mass=m, Id=0.5 * Ip + m * width * width / 12.0, Ip=Ip, name=name)

    def check(self, where: str) -> None:
        _finite(self.x, "x", where)
        for key in ("mass", "Id", "Ip"):
            _finite(getattr(self, key), key, where, minimum=0.0)
        if self.mass == 0 and self.Id == 0 and self.Ip == 0:
            raise ModelError(where, "mass", 0.0, "a disc with some inertia (mass, Id or Ip > 0)")


DAMPING_RULE = ("damping whose symmetric part is positive semidefinite (cyy >= 0, czz >= 0, cyy czz >= "
                "((cyz + czy)/2)^2: a bearing's damping must not feed energy into the shaft; stiffness may "
                "have any sign)")


def damping_not_dissipative(values: np.ndarray) -> tuple[int, str] | None:
    """(column, offending key) of the first column of ``values`` (8, n) in BEARING_COEFFICIENTS order
    whose damping matrix has an indefinite symmetric part, else None (relative slack 1e-12)."""
    cyy, cyz, czy, czz = values[4], values[5], values[6], values[7]
    scale = np.maximum(np.abs(cyy) + np.abs(czz) + np.abs(cyz) + np.abs(czy), 1e-300)
    for key, bad in (("cyy", cyy < -1e-12 * scale), ("czz", czz < -1e-12 * scale),
                     ("cyz", cyy * czz - 0.25 * (cyz + czy) ** 2 < -1e-12 * scale ** 2)):
        if np.any(bad):
            j = int(np.argmax(bad))
            return j, ("czy" if key == "cyz" and abs(czy[j]) > abs(cyz[j]) else key)
    return None


@dataclass
class Bearing:
    """A linear bearing or seal at ``x`` (m) acting on the lateral displacements (v, w) of the
    shaft node, relative to a pedestal's (``pedestal`` = its name) or to the ground (None).

    Force on the shaft: f = -K d - C d', K = [[kyy, kyz], [kzy, kzz]] (N/m), C = [[cyy, cyz],
    [czy, czz]] (N s/m).  Each coefficient is a number (constant) or a table over ``speeds``
    (rad/s, increasing): the coefficient at a speed is interpolated (``interpolation`` =
    "linear", "pchip" (shape-preserving cubic), "spline" (cubic spline, not-a-knot) or
    "smoothing-spline" (ROSS's convention: scipy's UnivariateSpline with s = number of points, which
    misses the table's points; :mod:`fem.rotor.tables`)); a speed outside the table follows
    ``extrapolate``: "refuse" (an error, the default), "hold" (the end values), "linear" (the
    interpolant's tangent line at the table's end) or "continue" (the interpolant's end pieces
    continued: ROSS's extrapolation with "smoothing-spline"), with a warning that names the bearing
    and the speeds outside its table.

    Signs: stiffness coefficients, direct or cross-coupled, take any sign (a seal's direct
    stiffness can be negative -- labyrinth seals, Lomakin effect --, so can an extrapolated
    table's; the modal analysis reports the statically unstable rotor this may give).  The damping
    matrix's symmetric part must be positive semidefinite at every table speed (cyy >= 0, czz >= 0,
    cyy czz >= ((cyz + czy)/2)^2): the power the bearing's damping force takes from the shaft,
    d'^T C d', is then >= 0, which the energy balances of run-ups count on; the skew part
    (cross-coupled damping of seals) does no work and is free.  A bearing needs some nonzero
    coefficient (cross-coupled stiffness alone: an aerodynamic cross-coupling).  ``k_axial``, ``c_axial`` (N/m, N s/m, >= 0): a thrust bearing on u
    (``dofs = "full"`` only)."""

    x: float
    kyy: float | Sequence[float] = 0.0
    kyz: float | Sequence[float] = 0.0
    kzy: float | Sequence[float] = 0.0
    kzz: float | Sequence[float] = 0.0
    cyy: float | Sequence[float] = 0.0
    cyz: float | Sequence[float] = 0.0
    czy: float | Sequence[float] = 0.0
    czz: float | Sequence[float] = 0.0
    speeds: Sequence[float] | None = None
    interpolation: str = "linear"
    extrapolate: str = "refuse"
    k_axial: float = 0.0
    c_axial: float = 0.0
    pedestal: str | None = None
    name: str = ""

    def check(self, where: str) -> None:
        _finite(self.x, "x", where)
        if self.interpolation not in INTERPOLATIONS:
            raise ModelError(where, "interpolation", self.interpolation, " | ".join(map(repr, INTERPOLATIONS)))
        if self.extrapolate not in EXTRAPOLATIONS:
            raise ModelError(where, "extrapolate", self.extrapolate, " | ".join(map(repr, EXTRAPOLATIONS)))
        table = self.table()
        if self.speeds is not None:
            grid = self.speed_grid
            if grid.size < 2 or not np.all(np.isfinite(grid)) or np.any(np.diff(grid) <= 0) or grid[0] < 0:
                raise ModelError(where, "speeds", list(np.atleast_1d(self.speeds)),
                                 "at least two increasing speeds >= 0 (rad/s)")
        for key in BEARING_COEFFICIENTS:
            if not np.all(np.isfinite(table[key])):
                raise ModelError(where, key, getattr(self, key), "finite numbers")
        bad = damping_not_dissipative(np.stack([table[k] for k in BEARING_COEFFICIENTS]))
        if bad is not None:
            j, key = bad
            at = f" at {self.speed_grid[j]:g} rad/s" if self.speeds is not None else ""
            raise ModelError(where, key, float(table[key][j]), DAMPING_RULE + at)
        if not any(np.any(table[k] != 0) for k in BEARING_COEFFICIENTS):
            raise ModelError(where, "kyy", 0.0, "a bearing with some nonzero coefficient (direct, or cross-coupled "
                             "only: an aerodynamic cross-coupling): all coefficients are zero")
        _finite(self.k_axial, "k_axial", where, minimum=0.0)
        _finite(self.c_axial, "c_axial", where, minimum=0.0)

    @property
    def speed_grid(self) -> np.ndarray:
        return np.asarray([] if self.speeds is None else self.speeds, dtype=float).ravel()

    @property
    def speed_dependent(self) -> bool:
        return self.speeds is not None

    def table(self) -> dict[str, np.ndarray]:
        """Each coefficient as an array over the speed grid (length 1 for a constant bearing)."""
        n = self.speed_grid.size if self.speeds is not None else 1
        out = {}
        for key in BEARING_COEFFICIENTS:
            raw = getattr(self, key)
            try:
                arr = np.asarray(raw, dtype=float)
            except (TypeError, ValueError):
                raise ModelError(f"bearing at x = {self.x!r}", key, raw, "a number or a list of numbers") from None
            if arr.ndim == 0:
                arr = np.full(n, float(arr))
            elif self.speeds is None:
                raise ModelError(f"bearing at x = {self.x!r}", key, list(arr),
                                 "a number, or give `speeds` for a speed-dependent table")
            elif arr.shape != (n,):
                raise ModelError(f"bearing at x = {self.x!r}", key, list(arr),
                                 f"one value per speed ({n} values, as many as `speeds`)")
            out[key] = arr
        return out


@dataclass
class Pedestal:
    """A support with its own mass between bearings and ground: ``mass`` (kg, in y and z),
    stiffness ``kyy``, ``kzz`` and damping ``cyy``, ``czz`` to ground (N/m, N s/m).  Bearings
    name it in their ``pedestal`` field; their forces act on the relative motion."""

    name: str
    mass: float
    kyy: float
    kzz: float
    cyy: float = 0.0
    czz: float = 0.0

    def check(self, where: str) -> None:
        if not isinstance(self.name, str) or not self.name:
            raise ModelError(where, "name", self.name, "a non-empty name (bearings refer to it)")
        _finite(self.mass, "mass", where, minimum=0.0, strict=True)
        for key in ("kyy", "kzz"):
            _finite(getattr(self, key), key, where, minimum=0.0, strict=True)
        for key in ("cyy", "czz"):
            _finite(getattr(self, key), key, where, minimum=0.0)


@dataclass
class Coupling:
    """A flexible coupling at ``x`` (m), which must be a junction of two shaft segments: the
    shaft is cut there and the two ends are joined by springs and dampers: ``k_lateral`` (N/m,
    v and w), ``k_angular`` (N m/rad, theta_y and theta_z), ``k_axial`` (N/m) and ``k_torsion``
    (N m/rad, ``dofs = "full"``), with dampers ``c_lateral``, ``c_angular`` likewise.  Its own
    ``mass``, ``Id``, ``Ip`` are split equally between the two ends.  Discs, bearings, supports and
    probes placed at ``x`` act on the left end (the end of the segment that ends there)."""

    x: float
    k_lateral: float
    k_angular: float
    k_axial: float = 0.0
    k_torsion: float = 0.0
    c_lateral: float = 0.0
    c_angular: float = 0.0
    mass: float = 0.0
    Id: float = 0.0
    Ip: float = 0.0
    name: str = ""

    def check(self, where: str, full: bool) -> None:
        _finite(self.x, "x", where)
        _finite(self.k_lateral, "k_lateral", where, minimum=0.0, strict=True)
        _finite(self.k_angular, "k_angular", where, minimum=0.0, strict=True)
        for key in ("k_axial", "k_torsion"):
            v = _finite(getattr(self, key), key, where, minimum=0.0)
            if full and v == 0:
                raise ModelError(where, key, v, "a stiffness > 0 for dofs = 'full' (else the coupling "
                                 "disconnects the shaft axially or in torsion)")
        for key in ("c_lateral", "c_angular", "mass", "Id", "Ip"):
            _finite(getattr(self, key), key, where, minimum=0.0)


@dataclass
class Support:
    """A rigid constraint at ``x`` (m): the listed DOFs of the node are held at zero
    (e.g. ("v", "w") for a rigid short bearing, all four lateral DOFs for a clamp)."""

    x: float
    dofs: Sequence[str] = ("v", "w")

    def check(self, where: str, fields: tuple[str, ...]) -> None:
        _finite(self.x, "x", where)
        if isinstance(self.dofs, str) or not len(self.dofs):
            raise ModelError(where, "dofs", self.dofs, "a non-empty list of DOF names, e.g. ['v', 'w']")
        for d in self.dofs:
            if d not in fields:
                raise ModelError(where, "dofs", d, "one of " + ", ".join(map(repr, fields)))


@dataclass
class Unbalance:
    """A mass unbalance at ``x`` (m): ``magnitude`` = m_u e (kg m) at angle ``phase`` (rad) from
    +y towards +z in the rotating frame.  At speed Omega it loads the node with
    f_y + i f_z = m_u e Omega^2 e^{i (Omega t + phase)}."""

    x: float
    magnitude: float
    phase: float = 0.0

    def check(self, where: str) -> None:
        _finite(self.x, "x", where)
        _finite(self.magnitude, "magnitude", where, minimum=0.0, strict=True)
        _finite(self.phase, "phase", where)


@dataclass
class Rotor:
    """The rotor description (what a ``[rotor]`` model file describes field for field).

    ``dofs``: "lateral" (v, w, theta_y, theta_z per node) or "full" (also u, theta_x)."""

    segments: list[ShaftSegment]
    discs: list[Disc] = field(default_factory=list)
    bearings: list[Bearing] = field(default_factory=list)
    pedestals: list[Pedestal] = field(default_factory=list)
    couplings: list[Coupling] = field(default_factory=list)
    supports: list[Support] = field(default_factory=list)
    dofs: str = "lateral"
    title: str = ""

    def __post_init__(self):
        self.segments, self.discs, self.bearings = list(self.segments), list(self.discs), list(self.bearings)
        self.pedestals, self.couplings, self.supports = list(self.pedestals), list(self.couplings), list(self.supports)
        if self.dofs not in DOF_SETS:
            raise ModelError("[rotor]", "dofs", self.dofs, " | ".join(map(repr, DOF_SETS)))
        for key, cls, table in (("segments", ShaftSegment, "segment"), ("discs", Disc, "disc"),
                                ("bearings", Bearing, "bearing"), ("pedestals", Pedestal, "pedestal"),
                                ("couplings", Coupling, "coupling"), ("supports", Support, "support")):
            for i, item in enumerate(getattr(self, key), 1):
                if not isinstance(item, cls):
                    raise ModelError(f"[[rotor.{table}]] #{i}", table, item, f"a fem.rotor.{cls.__name__}")
        if not self.segments:
            raise ModelError("[rotor]", "segment", [], "at least one shaft segment")
        for i, s in enumerate(self.segments, 1):
            s.check(f"[[rotor.segment]] #{i}")
        nodes = self.node_positions()
        L = self.length

        def on_shaft(x, where):
            if not -1e-12 * L <= x <= L * (1 + 1e-12):
                raise ModelError(where, "x", x, f"a position on the shaft, 0 <= x <= {L:g} m")
            k = int(np.argmin(np.abs(nodes - x)))
            if abs(nodes[k] - x) > 1e-9 * L:
                near = ", ".join(f"{nodes[j]:.6g}" for j in sorted({max(k - 1, 0), k, min(k + 1, nodes.size - 1)}))
                raise ModelError(where, "x", x, f"a node position (segment ends and element boundaries); "
                                 f"nearest nodes: {near} m")

        for i, d in enumerate(self.discs, 1):
            w = f"[[rotor.disc]] #{i}"
            d.check(w)
            on_shaft(d.x, w)
        names = [p.name for p in self.pedestals]
        for i, p in enumerate(self.pedestals, 1):
            p.check(f"[[rotor.pedestal]] #{i}")
        if len(set(names)) != len(names):
            dup = next(n for n in names if names.count(n) > 1)
            raise ModelError("[[rotor.pedestal]]", "name", dup, "unique pedestal names")
        used = set()
        numbers = {}                        # bearings computed from their geometry are numbered per table
        for b in self.bearings:
            table = getattr(b, "kind", "bearing")
            numbers[table] = numbers.get(table, 0) + 1
            w = f"[[rotor.{table}]] #{numbers[table]}"
            b.check(w)
            on_shaft(b.x, w)
            if b.pedestal is not None:
                if b.pedestal not in names:
                    raise ModelError(w, "pedestal", b.pedestal, "the name of a [[rotor.pedestal]]: "
                                     + (", ".join(map(repr, names)) or "none defined"))
                used.add(b.pedestal)
            if (b.k_axial or b.c_axial) and self.dofs != "full":
                raise ModelError(w, "k_axial", b.k_axial, "0 unless dofs = 'full' (no axial DOF in a lateral model)")
        for p in self.pedestals:
            if p.name not in used:
                raise ModelError("[[rotor.pedestal]]", "name", p.name, "a pedestal that some bearing uses")
        junctions = np.cumsum([s.length for s in self.segments])[:-1]
        for i, c in enumerate(self.couplings, 1):
            w = f"[[rotor.coupling]] #{i}"
            c.check(w, self.dofs == "full")
            if not junctions.size or np.min(np.abs(junctions - c.x)) > 1e-9 * L:
                raise ModelError(w, "x", c.x, "a junction of two shaft segments: "
                                 + (", ".join(f"{j:.6g}" for j in junctions) or "this shaft has one segment") + " m")
        xs = [c.x for c in self.couplings]
        if len(xs) != len(set(np.round(np.asarray(xs) / L, 9))):
            raise ModelError("[[rotor.coupling]]", "x", xs, "one coupling per junction")
        for i, s in enumerate(self.supports, 1):
            w = f"[[rotor.support]] #{i}"
            s.check(w, self.fields)
            on_shaft(s.x, w)

    # ------------------------------------------------------------------ geometry
    @property
    def fields(self) -> tuple[str, ...]:
        return DOF_SETS[self.dofs]

    @property
    def length(self) -> float:
        return float(sum(s.length for s in self.segments))

    def node_positions(self) -> np.ndarray:
        """x of the shaft nodes (each segment's elements equal; a coupling's two ends share one x)."""
        xs = [np.zeros(1)]
        x0 = 0.0
        for s in self.segments:
            xs.append(x0 + s.length * np.arange(1, s.elements + 1) / s.elements)
            x0 += s.length
        return np.concatenate(xs)

    @property
    def n_elements(self) -> int:
        return int(sum(s.elements for s in self.segments))


def rpm(speed_rpm):
    """rev/min -> rad/s."""
    return np.asarray(speed_rpm, dtype=float) * (math.pi / 30.0) if np.ndim(speed_rpm) else float(speed_rpm) * math.pi / 30.0


def to_rpm(speed_rad_s):
    """rad/s -> rev/min."""
    return np.asarray(speed_rad_s, dtype=float) * (30.0 / math.pi) if np.ndim(speed_rad_s) else float(speed_rad_s) * 30.0 / math.pi
