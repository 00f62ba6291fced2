"""Regular-structure drives (§10.4): n identical blocks [shaft segment c0, disc J0 carrying a
mechanism Pi'-c-m], closed-form spectra, pass/stop bands and the corrected forced response.

Geometry per boundary case (discs j = 1..n, mechanisms on the discs):

=================  ===========================================  ===========================
boundary           chain                                         gamma_r
=================  ===========================================  ===========================
clamped-free       clamp-c0-J-c0-J ... c0-J (case 2, Fig. 10.2)  pi (2r-1)/(2n+1)    (10.38)
clamped-clamped    clamp-c0-J- ... -J-c0-clamp (case 1, §10.4:    r pi/(n+1)         (10.34)
                   n discs, n+1 segments)
free-free          J-c0-J- ... -c0-J (n-1 segments)              (r-1) pi/n, r = 1..n
free-clamped       J-c0-J- ... -J-c0-clamp (mirror of case 2)    pi (2r-1)/(2n+1)
=================  ===========================================  ===========================

With xi = cos gamma = 1 - J*(p) p^2/(2 c0) (10.35)-(10.36) and J*(p) (10.16) the frequency
equation is biquadratic in p: J0 s^2 - (J0 k^2 + m Pi'^2 k^2 + kappa) s + kappa k^2 = 0,
s = p^2, kappa = 4 c0 sin^2(gamma/2).  Rigid mechanisms: p_r = 2 p0 sin(gamma_r/2),
p0 = sqrt(c0/J) (10.37), (10.39).  Stop band (J* < 0): k < p < k sqrt(1 + m Pi'^2/J0).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ModelError
from .chain import Chain
from .elements import Inertia, Spring, mechanism_branch

BOUNDARY_CASES = ("clamped-free", "clamped-clamped", "free-free", "free-clamped")
BOOK_CASE = {"clamped-clamped": 1, "clamped-free": 2, "free-free": 3, "free-clamped": 4}


def check_boundary(boundary: str, where: str = "[drive]") -> str:
    if boundary not in BOUNDARY_CASES:
        raise ModelError(where, "boundary", boundary, " | ".join(map(repr, BOUNDARY_CASES))
                         + " (book cases 2, 1, 3, 4)")
    return boundary


def gammas(n: int, boundary: str) -> np.ndarray:
    """Shaft shape parameters gamma_r, r = 1..n ((10.34), (10.38); free-free includes r = 1, gamma = 0)."""
    check_n(n)
    check_boundary(boundary)
    r = np.arange(1, n + 1, dtype=float)
    if boundary == "clamped-clamped":
        return r * np.pi / (n + 1)
    if boundary == "free-free":
        return (r - 1) * np.pi / n
    return np.pi * (2 * r - 1) / (2 * n + 1)


def check_n(n, where: str = "[drive]") -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ModelError(where, "n", n, "an integer >= 1 (number of identical mechanisms)")
    return int(n)


def rigid_ratios(n: int, boundary: str) -> np.ndarray:
    """p_r/p0 = 2 sin(gamma_r/2) for constant J* ((10.37) case 1, (10.39) case 2)."""
    return 2 * np.sin(gammas(n, boundary) / 2)


def pass_band(n: int, boundary: str) -> tuple[float, float]:
    """Bounds of p_r/p0 for rigid mechanisms: (lowest root, 2) ((10.37)/(10.39): p_r < 2 p0)."""
    g = gammas(n, boundary)
    first = g[g > 0][0] if np.any(g > 0) else 0.0
    return 2 * np.sin(first / 2), 2.0


@dataclass(frozen=True)
class RegularDrive:
    """n identical blocks: shaft segment c0, disc J0, mechanism (m, c, Pi'); ``output`` of the
    mechanism "free" (Fig. 10.2) or "grounded" (output link sprung to the frame, (10.13))."""

    n: int
    c0: float
    J0: float
    m: float
    c: float
    ratio: float
    boundary: str = "clamped-free"
    output: str = "free"

    def __post_init__(self):
        check_n(self.n)
        check_boundary(self.boundary)
        for key in ("c0", "m", "c"):
            v = getattr(self, key)
            if not (isinstance(v, (int, float)) and v > 0 and (np.isfinite(v) or key == "c")):
                raise ModelError("[drive]", key, v, "a finite number > 0")
        if not self.J0 >= 0:
            raise ModelError("[drive]", "J0", self.J0, "a number >= 0")
        if self.ratio == 0 or not np.isfinite(self.ratio):
            raise ModelError("[drive.mechanism]", "ratio", self.ratio, "a finite non-zero Pi' (m/rad)")
        if self.output not in ("free", "grounded"):
            raise ModelError("[drive.mechanism]", "output", self.output, "'free' | 'grounded'")
        if self.output == "free" and self.J0 == 0:
            raise ModelError("[drive]", "J0", 0.0, "a disc inertia > 0 (the closed forms divide by J0)")

    @classmethod
    def from_mechanisms(cls, c0, J0, m, c, ratio, boundary="clamped-free", output="free", rtol=1e-12):
        """Build from per-block lists; the closed forms need identical blocks (else an error)."""
        vals = {"c0": c0, "J0": J0, "m": m, "c": c, "ratio": ratio}
        arrs = {k: np.atleast_1d(np.asarray(v, dtype=float)) for k, v in vals.items()}
        n = max(a.size for a in arrs.values())
        for k, a in arrs.items():
            if a.size not in (1, n):
                raise ModelError("regular drive", k, a.tolist(), f"one value or {n} values")
            if np.any(np.abs(a - a[0]) > rtol * np.abs(a[0])):
                raise ModelError("regular drive", k, a.tolist(),
                                 "identical values for every block (the regular-structure formulas (10.29)-(10.46) "
                                 "assume identical mechanisms; use the transfer-matrix or FE representation)")
        return cls(n=n, boundary=boundary, output=output, **{k: float(a[0]) for k, a in arrs.items()})

    # ------------------------------------------------------------ block functions
    @property
    def k(self) -> float:
        """Partial frequency of the mechanism, input held: sqrt(c/m)."""
        return float(np.sqrt(self.c / self.m))

    @property
    def p0(self) -> float:
        """sqrt(c0/J0) (10.37) with J0 the bare disc."""
        return float(np.sqrt(self.c0 / self.J0))

    @property
    def p0_rigid(self) -> float:
        """sqrt(c0/(J0 + m Pi'^2)): rigid mechanisms (c -> infinity in (10.16))."""
        return float(np.sqrt(self.c0 / (self.J0 + self.m * self.ratio**2)))

    def J_star(self, p):
        """Reduced disc inertia (10.16) (corrected sign, digest flag 1 of 10.2):
        free output J0 + m Pi'^2/(1 - p^2/k^2); grounded output J0 - c Pi'^2/p^2."""
        p = np.asarray(p, dtype=float)
        with np.errstate(divide="ignore"):
            if self.output == "free":
                return self.J0 + self.m * self.ratio**2 / (1 - p**2 / self.k**2)
            return self.J0 - self.c * self.ratio**2 / p**2

    def xi(self, p):
        """Half trace of the block matrix (10.31), (10.35): xi = 1 - J*(p) p^2 / (2 c0)."""
        return 1 - self.J_star(p) * np.asarray(p, float) ** 2 / (2 * self.c0)

    def stop_band(self) -> tuple[float, float]:
        """Band with J* < 0 (free output): (k, k sqrt(1 + m Pi'^2/J0)); no natural frequency there."""
        if self.output != "free":
            raise ModelError("[drive.mechanism]", "output", self.output, "'free' for the stop band of J*(p)")
        return self.k, self.k * float(np.sqrt(1 + self.m * self.ratio**2 / self.J0))

    # ------------------------------------------------------------ spectra
    def natural_frequencies(self) -> np.ndarray:
        """All natural frequencies in increasing order: the two roots per gamma_r of the
        biquadratic (10.36) with (10.16) (free output: 2n values; grounded: n values)."""
        if np.isinf(self.c):
            return self.rigid_frequencies()
        g = gammas(self.n, self.boundary)
        kappa = 4 * self.c0 * np.sin(g / 2) ** 2
        if self.output == "grounded":
            s = (kappa + self.c * self.ratio**2) / self.J0
            return np.sort(np.sqrt(s))
        k2, J0, mP = self.k**2, self.J0, self.m * self.ratio**2
        b = J0 * k2 + mP * k2 + kappa
        disc = np.sqrt(b**2 - 4 * J0 * kappa * k2)
        s_lo = 2 * kappa * k2 / (b + disc)     # stable form of (b - disc)/(2 J0)
        s_hi = (b + disc) / (2 * J0)
        return np.sort(np.sqrt(np.concatenate([s_lo, s_hi])))

    def pass_bands(self) -> tuple[tuple[float, float], tuple[float, float]]:
        """Frequency bands with |xi(p)| <= 1 (trigonometric propagation, (10.32)), free output:
        (0, p_1max) below k and (p_*, p_2max) above the stop band; p_1max, p_2max are the roots
        of (10.36) at xi = -1 (kappa = 4 c0).  Every natural frequency lies in them for any n;
        between p_1max and k and above p_2max, xi < -1 (alternating hyperbolic zones)."""
        if self.output != "free" or np.isinf(self.c):
            raise ModelError("[drive.mechanism]", "output", self.output, "an elastic mechanism with a free output")
        k2, J0, mP, kappa = self.k**2, self.J0, self.m * self.ratio**2, 4 * self.c0
        b = J0 * k2 + mP * k2 + kappa
        disc = np.sqrt(b**2 - 4 * J0 * kappa * k2)
        return (0.0, float(np.sqrt(2 * kappa * k2 / (b + disc)))), (self.stop_band()[1], float(np.sqrt((b + disc) / (2 * J0))))

    def rigid_frequencies(self) -> np.ndarray:
        """Rigid mechanisms (10.37)/(10.39): p_r = 2 p0* sin(gamma_r/2), p0* = sqrt(c0/(J0 + m Pi'^2))."""
        return self.p0_rigid * rigid_ratios(self.n, self.boundary)

    # ------------------------------------------------------------ chain
    def chain(self, load: complex = 0.0) -> Chain:
        """The transfer-matrix chain of this drive (force ``load`` on every mechanism output)."""
        if np.isinf(self.c):
            disc = [Inertia(self.J0 + self.m * self.ratio**2)]
        else:
            disc = [Inertia(self.J0), mechanism_branch(self.m, self.c, self.ratio, end=self.output, load=load)]
        els = []
        start, end = self.boundary.split("-")
        for j in range(self.n):
            if j > 0 or start == "clamped":
                els.append(Spring(self.c0))
            els += disc
        if end == "clamped":
            els.append(Spring(self.c0))
        return Chain(els, start=start, end=end)

    # ------------------------------------------------------------ forced (corrected)
    def forced_amplitudes(self, omega: float, F: float = 1.0) -> np.ndarray:
        """Disc amplitudes a_0j, j = 1..n, for a force F on every mechanism output (free output),
        by the CORRECTED closed forms of (10.40)-(10.46) (digest errata):

            a_0j = [F / (D_j J*_0 w^2)] [cos j gamma - 1 + t sin j gamma],
            D_j = (1 - w^2/k^2)/Pi',   t = tan((n + 1/2) gamma) (case 2) or tan((n+1) gamma/2) (case 1),

        gamma = arccos(xi) (complex in the hyperbolic zones |xi| > 1).  The prefactor equals
        F Pi' / (w^2 [J0 (1 - w^2/k^2) + m Pi'^2]).  At w = k every disc has a_0j = -F/(c Pi')."""
        if self.output != "free" or self.boundary not in ("clamped-free", "clamped-clamped"):
            raise ModelError("[drive]", "boundary", self.boundary,
                             "'clamped-free' or 'clamped-clamped' with a free mechanism output for the closed-form "
                             "forced response (10.40)-(10.46)")
        w = float(omega)
        j = np.arange(1, self.n + 1)
        if np.isclose(w, self.k, rtol=1e-14, atol=0):
            return np.full(self.n, -F / (self.c * self.ratio))
        pref = F * self.ratio / (w**2 * (self.J0 * (1 - w**2 / self.k**2) + self.m * self.ratio**2))
        g = np.arccos(complex(self.xi(w)))
        t = np.tan((self.n + 0.5) * g) if self.boundary == "clamped-free" else np.tan((self.n + 1) * g / 2)
        a = pref * (np.cos(j * g) - 1 + t * np.sin(j * g))
        return a.real
