"""Description of a drive of regular structure (§10.2, §10.4, §10.5) and its ``[drive]`` table.

A main shaft (lumped: segment stiffness c0 and disc inertia J0 per block; or distributed:
length L, torsional stiffness GI, inertia per length rho, optional disc J0 at each
mechanism) carries n identical 1-DOF mechanisms (output mass m, stiffness c, first
transfer function Pi').  Mechanism j sits on station j of the shaft; the stations divide
the shaft into equal segments as in the regular chains of :mod:`discrete.transfer.regular`
(clamped-free: x_j = j L/n; clamped-clamped: j L/(n+1); free-free: (j-1) L/(n-1);
free-clamped: (j-1) L/n).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from discrete.errors import ModelError
from discrete.schema import check_keys, choice, number
from discrete.transfer.regular import BOUNDARY_CASES, check_boundary, check_n

REPRESENTATIONS = ("discrete", "transfer-matrix", "continuum")
DRIVE_KEYS = {"n", "boundary", "representation", "shaft", "mechanism", "load", "continuum"}
SHAFT_KEYS = {"lumped": {"type", "c0", "J0"},
              "distributed": {"type", "length", "GI", "rho", "J0", "elements", "order", "mass"}}
MECHANISM_KEYS = {"m", "c", "k", "ratio", "output"}
CONTINUUM_KEYS = {"elements", "order", "length"}
LOAD_KEYS = {"force"}


@dataclass(frozen=True)
class LumpedShaft:
    c0: float            # stiffness of one segment (N m/rad)
    J0: float            # disc inertia at each mechanism (kg m^2)
    kind = "lumped"


@dataclass(frozen=True)
class DistributedShaft:
    length: float        # m
    GI: float            # N m^2
    rho: float           # kg m (inertia per length)
    J0: float = 0.0      # optional disc at each mechanism
    elements: int = 8    # FE elements per segment (discrete representation)
    order: int = 2
    mass: str = "consistent"
    kind = "distributed"


@dataclass(frozen=True)
class Mechanism:
    m: float
    c: float
    ratio: float
    output: str = "free"

    @property
    def k(self) -> float:
        return float(np.sqrt(self.c / self.m))

    @property
    def rigid(self) -> bool:
        """c = inf: rigid mechanism, its output mass reduced to the disc as m Pi'^2 ((10.16), c -> inf)."""
        return bool(np.isinf(self.c))


@dataclass(frozen=True)
class DriveModel:
    n: int
    shaft: LumpedShaft | DistributedShaft
    mechanism: Mechanism
    boundary: str = "clamped-free"
    representation: str = "discrete"
    force: float = 0.0                 # force amplitude on every mechanism output (N)
    continuum_elements: int = 64
    continuum_order: int = 2
    continuum_length: float = 1.0      # notional length of the continuum of a lumped shaft (per segment)
    title: str = ""

    def __post_init__(self):
        check_n(self.n)
        check_boundary(self.boundary)
        if self.boundary == "free-free" and self.n < 2:
            raise ModelError("[drive]", "n", self.n, "n >= 2 for boundary = 'free-free' (n-1 shaft segments)")
        choice(self.representation, "representation", "[drive]", REPRESENTATIONS)
        if self.mechanism.ratio == 0:
            raise ModelError("[drive.mechanism]", "ratio", 0.0, "a non-zero first transfer function Pi' (m/rad)")

    # ------------------------------------------------------------ geometry
    @property
    def n_segments(self) -> int:
        return {"clamped-free": self.n, "clamped-clamped": self.n + 1, "free-free": self.n - 1,
                "free-clamped": self.n}[self.boundary]

    @property
    def start(self) -> str:
        return self.boundary.split("-")[0]

    @property
    def end(self) -> str:
        return self.boundary.split("-")[1]

    @property
    def length(self) -> float:
        if isinstance(self.shaft, DistributedShaft):
            return self.shaft.length
        return self.continuum_length * self.n_segments

    @property
    def segment_length(self) -> float:
        return self.length / self.n_segments

    def stations(self) -> np.ndarray:
        """Positions of the n mechanisms along the shaft."""
        h = self.segment_length
        j = np.arange(1, self.n + 1)
        return (j if self.start == "clamped" else j - 1) * h

    # ------------------------------------------------------------ smeared parameters (§10.5)
    def smeared(self) -> dict:
        """Pseudo-medium parameters: GI, rho (shaft + smeared discs n J0/L), m_bar = n m/L,
        c_bar = n c/L, Pi', L."""
        L = self.length
        if isinstance(self.shaft, DistributedShaft):
            GI, rho = self.shaft.GI, self.shaft.rho + self.n * self.shaft.J0 / L
        else:
            GI, rho = self.shaft.c0 * self.segment_length, self.n * self.shaft.J0 / L
        me = self.mechanism
        return {"GI": GI, "rho": rho, "m_bar": self.n * me.m / L, "c_bar": self.n * me.c / L,
                "ratio": me.ratio, "L": L, "k": me.k, "rigid": me.rigid}

    def with_n(self, n: int) -> "DriveModel":
        """The same drive with n mechanisms, keeping the totals fixed (total mechanism mass n m,
        partial frequency k, total disc inertia, the shaft's length, total stiffness and inertia)
        -- the sequence that converges to the pseudo-medium."""
        n = check_n(n)
        probe = replace(self, n=n)
        scale = self.n / n
        me = self.mechanism
        mech = replace(me, m=me.m * scale, c=me.c * scale)
        if isinstance(self.shaft, DistributedShaft):
            shaft = replace(self.shaft, J0=self.shaft.J0 * scale)
            return replace(probe, shaft=shaft, mechanism=mech)
        # lumped: per-segment stiffness scales with the number of segments, discs with 1/n
        seg_ratio = probe.n_segments / self.n_segments
        shaft = LumpedShaft(c0=self.shaft.c0 * seg_ratio, J0=self.shaft.J0 * scale)
        return replace(probe, shaft=shaft, mechanism=mech,
                       continuum_length=self.continuum_length / seg_ratio)

    def describe(self) -> str:
        me = self.mechanism
        if isinstance(self.shaft, DistributedShaft):
            s = (f"distributed shaft L = {self.shaft.length:g} m, GI = {self.shaft.GI:g} N m^2, rho = {self.shaft.rho:g} kg m"
                 + (f", discs J0 = {self.shaft.J0:g}" if self.shaft.J0 else ""))
        else:
            s = f"lumped shaft c0 = {self.shaft.c0:g} N m/rad, J0 = {self.shaft.J0:g} kg m^2"
        return (f"drive: n = {self.n} mechanisms (m = {me.m:g} kg, c = {me.c:g} N/m, k = {me.k:g} rad/s, "
                f"Pi' = {me.ratio:g} m/rad, output {me.output}), {s}, boundary {self.boundary}")


def parse_drive(doc: dict) -> DriveModel:
    """Build a :class:`DriveModel` from a parsed model file (``[drive]`` and its sub-tables)."""
    from . import TOP_LEVEL_KEYS

    check_keys(doc, TOP_LEVEL_KEYS, "model file")
    d = doc.get("drive")
    if not isinstance(d, dict):
        raise ModelError("model file", "drive", d, "a [drive] table")
    where = "[drive]"
    check_keys(d, DRIVE_KEYS, where)
    if "n" not in d:
        raise ModelError(where, "n", None, "the number of identical mechanisms (required)")
    n = d["n"]
    if isinstance(n, bool) or not isinstance(n, int) or n < 1:
        raise ModelError(where, "n", n, "an integer >= 1 (number of identical mechanisms)")
    boundary = d.get("boundary", "clamped-free")
    if boundary not in BOUNDARY_CASES:
        raise ModelError(where, "boundary", boundary, " | ".join(map(repr, BOUNDARY_CASES)))
    rep = choice(d.get("representation", "discrete"), "representation", where, REPRESENTATIONS)

    sh = d.get("shaft")
    w = "[drive.shaft]"
    if not isinstance(sh, dict):
        raise ModelError(where, "shaft", sh, "a [drive.shaft] table")
    kind = choice(sh.get("type", "lumped"), "type", w, ("lumped", "distributed"))
    check_keys(sh, SHAFT_KEYS[kind], w, hints={k: f"a key of type = '{o}' shafts" for o in SHAFT_KEYS if o != kind
                                                for k in SHAFT_KEYS[o] - SHAFT_KEYS[kind]})
    if kind == "lumped":
        for key in ("c0", "J0"):
            if key not in sh:
                raise ModelError(w, key, None, "required for a lumped shaft")
        shaft = LumpedShaft(c0=number(sh["c0"], "c0", w, positive=True), J0=number(sh["J0"], "J0", w, positive=True))
    else:
        for key in ("length", "GI", "rho"):
            if key not in sh:
                raise ModelError(w, key, None, "required for a distributed shaft")
        shaft = DistributedShaft(length=number(sh["length"], "length", w, positive=True),
                                 GI=number(sh["GI"], "GI", w, positive=True),
                                 rho=number(sh["rho"], "rho", w, nonnegative=True),
                                 J0=number(sh.get("J0", 0.0), "J0", w, nonnegative=True),
                                 elements=number(sh.get("elements", 8), "elements", w, positive=True, integer=True),
                                 order=int(choice(sh.get("order", 2), "order", w, (1, 2))),
                                 mass=choice(sh.get("mass", "consistent"), "mass", w, ("consistent", "lumped")))
        if shaft.rho == 0 and shaft.J0 == 0:
            raise ModelError(w, "rho", 0.0, "rho > 0 or discs J0 > 0 (the shaft needs inertia)")

    me = d.get("mechanism")
    w = "[drive.mechanism]"
    if not isinstance(me, dict):
        raise ModelError(where, "mechanism", me, "a [drive.mechanism] table")
    check_keys(me, MECHANISM_KEYS, w)
    for key in ("m", "ratio"):
        if key not in me:
            raise ModelError(w, key, None, "required")
    m = number(me["m"], "m", w, positive=True)
    if ("c" in me) == ("k" in me):
        raise ModelError(w, "c", me.get("c"), "exactly one of c (N/m) or k = sqrt(c/m) (rad/s)")
    key = "c" if "c" in me else "k"
    if isinstance(me[key], float) and me[key] == float("inf"):
        c = float("inf")     # rigid mechanism (TOML: c = inf)
    else:
        v = number(me[key], key, w, positive=True)
        c = v if key == "c" else m * v**2
    ratio = number(me["ratio"], "ratio", w)
    if ratio == 0:
        raise ModelError(w, "ratio", me["ratio"], "a non-zero first transfer function Pi' (m/rad)")
    mech = Mechanism(m=m, c=c, ratio=ratio, output=choice(me.get("output", "free"), "output", w, ("free", "grounded")))

    force = 0.0
    if "load" in d:
        ld = d["load"]
        check_keys(ld, LOAD_KEYS, "[drive.load]")
        force = number(ld.get("force", 0.0), "force", "[drive.load]")
    co = d.get("continuum", {})
    check_keys(co, CONTINUUM_KEYS, "[drive.continuum]")
    ce = number(co.get("elements", 64), "elements", "[drive.continuum]", positive=True, integer=True)
    corder = int(choice(co.get("order", 2), "order", "[drive.continuum]", (1, 2)))
    clen = number(co.get("length", 1.0), "length", "[drive.continuum]", positive=True)
    if "length" in co and kind == "distributed":
        raise ModelError("[drive.continuum]", "length", co["length"],
                         "only for a lumped shaft (a distributed shaft has its own length)")
    return DriveModel(n=n, shaft=shaft, mechanism=mech, boundary=boundary, representation=rep, force=force,
                      continuum_elements=ce, continuum_order=corder, continuum_length=clen,
                      title=str(doc.get("title", "")))
