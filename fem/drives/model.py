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
from discrete.transfer.regular import check_boundary, check_n

REPRESENTATIONS = ("discrete", "transfer-matrix", "continuum")


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
        if self.representation not in REPRESENTATIONS:
            raise ModelError("[drive]", "representation", self.representation, " | ".join(map(repr, REPRESENTATIONS)))
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
