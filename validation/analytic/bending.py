"""Euler-Bernoulli beams and 2-mass flexibility models: book §3.3 (Table 3.1), §4.5, §4.7, §4.11.

Book notation: ``sigma`` (here ``beta``) with ``sigma^4 = m k^2 / (E I L)`` (4.59), ``m`` the beam
mass; here ``beta^4 = mass_per_length * omega^2 / EI``.  Sign convention (§4.11): ``y`` positive
up, bending moment ``EI y''`` and shear force ``EI y'''``.  Angular frequencies in rad/s.
"""
from __future__ import annotations

import numpy as np
from scipy.optimize import brentq

EB_BCS = ("pinned-pinned", "clamped-free", "clamped-pinned", "clamped-clamped",
          "free-free", "pinned-free")

_XTOL = 1e-14


def _clamped_free(x):
    return np.cos(x) + 1.0 / np.cosh(x)          # cos x cosh x = -1   (4.72)


def _clamped_clamped(x):
    return np.cos(x) - 1.0 / np.cosh(x)          # cos x cosh x = +1


def _clamped_pinned(x):
    return np.sin(x) - np.cos(x) * np.tanh(x)    # tan x = tanh x


def euler_bernoulli_roots(bc: str, n: int) -> np.ndarray:
    """First ``n`` positive roots ``beta_r L`` (the book's ``sigma_r L``) for a uniform beam.

    Frequency equations, each solved by brentq in a form divided by ``cosh x`` so that large
    roots stay accurate:

    - ``pinned-pinned``: ``sin x = 0`` -> ``r pi`` (4.64);
    - ``clamped-free``: ``cos x cosh x = -1`` (4.72), root ``r`` in ``((r-1) pi, r pi)``;
    - ``clamped-pinned`` and ``pinned-free``: ``tan x = tanh x``, root ``r`` in
      ``(r pi, r pi + pi/2)`` (pinned-free also has a rigid rotation about the pin, not included);
    - ``clamped-clamped`` and ``free-free``: ``cos x cosh x = 1``, root ``r`` in
      ``(r pi, (r+1) pi)`` (free-free also has two rigid-body zero modes, not included).
    """
    r = np.arange(1, n + 1, dtype=float)
    if bc == "pinned-pinned":
        return r * np.pi
    if bc == "clamped-free":
        f, lows, width = _clamped_free, (r - 1.0) * np.pi, np.pi
    elif bc in ("clamped-pinned", "pinned-free"):
        f, lows, width = _clamped_pinned, r * np.pi, np.pi / 2.0
    elif bc in ("clamped-clamped", "free-free"):
        f, lows, width = _clamped_clamped, r * np.pi, np.pi
    else:
        raise ValueError(f"bc = {bc!r} is not valid; allowed: {', '.join(EB_BCS)}")
    return np.array([brentq(f, lo, lo + width, xtol=_XTOL) for lo in lows])


def euler_bernoulli_omegas(EI, mass_per_length, length, roots) -> np.ndarray:
    """``omega_r = (beta_r L)^2 / L^2 * sqrt(EI / mass_per_length)``.

    (4.65)/(4.73) ``k_r = sigma_r^2 sqrt(E I L / m)`` with ``m = mass_per_length * L`` (the seed's
    intermediate ``sigma_r^2 sqrt(EI/m)`` in (4.65) is a misprint for ``sqrt(EIL/m)``).
    """
    roots = np.asarray(roots, dtype=float)
    return roots**2 / length**2 * np.sqrt(EI / mass_per_length)


def _tip_mass_det(x, mass_ratio: float, inertia_ratio: float):
    """Reduced 2x2 determinant for the clamped beam with tip mass/inertia (see caller)."""
    x = np.asarray(x, dtype=float)
    c, s, e = np.cos(x), np.sin(x), np.exp(-x)
    one = np.ones_like(x)
    # Shape functions (cos, sin, e^{-xi}, e^{xi - x}) of xi = beta * position and their
    # derivatives d^k/d(xi)^k at the tip xi = x.
    d0 = (c, s, e, one)
    d1 = (-s, c, -e, one)
    d2 = (-c, -s, e, one)
    d3 = (s, -c, -e, one)
    jx3, etax = inertia_ratio * x**3, mass_ratio * x
    moment = [(p - jx3 * q) / (1.0 + jx3) for p, q in zip(d2, d1)]
    shear = [(p + etax * q) / (1.0 + etax) for p, q in zip(d3, d0)]

    def reduce(row):
        # clamp A(0) = A'(0) = 0  ->  C1 = -C3 - e C4,  C2 = C3 - e C4
        return row[2] - row[0] + row[1], row[3] - e * (row[0] + row[1])

    (m3, m4), (s3, s4) = reduce(moment), reduce(shear)
    return m3 * s4 - m4 * s3


def cantilever_tip_mass_roots(mass_ratio: float, n: int, inertia_ratio: float = 0.0) -> np.ndarray:
    """First ``n`` roots ``x = beta L`` of a clamped-free beam with a tip mass and rotary inertia.

    ``mass_ratio = M / (mass_per_length L)``, ``inertia_ratio = J_t / (mass_per_length L^3)``;
    ``omega = x^2 / L^2 sqrt(EI / mass_per_length)``.  Sign convention (``y`` up, ``EI y''`` =
    moment, ``EI y'''`` = shear, as in §4.11); the tip conditions follow from the variation of
    ``T - V`` with ``T`` including ``M ydot(L)^2 / 2 + J_t ydot'(L)^2 / 2``:
    ``EI A''(L) = +J_t omega^2 A'(L)`` and ``EI A'''(L) = -M omega^2 A(L)``.

    The general solution (4.60) is used with ``ch, sh`` recombined into ``e^{-beta x}`` and
    ``e^{beta (x - L)}`` (same solution space; O(1) entries, so no cancellation for high modes).
    The clamp conditions eliminate two constants (as in (4.69)-(4.70)); the remaining 2x2
    determinant, with the tip rows divided by the positive scales ``1 + j x^3`` and
    ``1 + eta x``, is scanned for sign changes on a fine grid and refined with brentq.
    ``mass_ratio = inertia_ratio = 0`` gives (4.72); ``mass_ratio -> inf`` makes the first root
    tend to 0 and the next ones tend to the clamped-pinned roots.
    """
    if mass_ratio < 0.0 or inertia_ratio < 0.0:
        raise ValueError(f"mass_ratio = {mass_ratio!r}, inertia_ratio = {inertia_ratio!r} are not "
                         "valid; allowed: numbers >= 0")

    def f(x):
        return _tip_mass_det(x, mass_ratio, inertia_ratio)

    # Dunkerley-type lower bound on the first root: 1/x1^4 <= 1/1.8751^4 + eta/3 + j.
    x_low = (1.0 / (1.0 / 1.8751**4 + mass_ratio / 3.0 + inertia_ratio)) ** 0.25
    step = min(0.02, 0.25 * x_low)
    start = 0.5 * x_low
    roots: list[float] = []
    while len(roots) < n:
        grid = start + step * np.arange(2001)
        vals = f(grid)
        for i in np.nonzero(np.sign(vals[:-1]) * np.sign(vals[1:]) < 0.0)[0]:
            roots.append(brentq(f, grid[i], grid[i + 1], xtol=_XTOL))
        start = grid[-1]
    return np.array(roots[:n])


def influence_coefficients(case: int, l: float, a: float, c: float,
                           EI: float = 1.0) -> tuple[float, float, float]:
    """Table 3.1 influence (flexibility) coefficients ``(e11, e22, e12)`` for a beam of span ``l``.

    Points are measured from the left end (clamp where there is one); ``b = l - a``,
    ``d = l - c`` except in row 1:

    1. cantilever, clamp at 0: points at ``a`` and ``c`` (the table calls the second one ``b``):
       ``e11 = a^3/3``, ``e22 = c^3/3``, ``e12 = a^2/2 (c - a/3)``;
    2. simply supported: ``e11 = a^2 b^2/(3l)``, ``e22 = c^2 d^2/(3l)``,
       ``e12 = a d (l^2 - a^2 - d^2)/(6l)``;
    3. clamped (0) - pinned (l): ``e11 = a^3/3 [1 - a(2l+b)^2/(4l^3)]``, ``e22`` likewise with
       ``c, d``, ``e12 = a^2/2 [c - a/3 - 3c^2/(2l^3) (l - a/3)(l - c/3)]``;
    4. clamped-clamped: ``e11 = a^3 b^3/(3l^3)``, ``e22 = c^3 d^3/(3l^3)``,
       ``e12 = a d/(6l^3) [b c (l f + 2 a d) - l^2 f^2]`` with ``f = c - a`` (undefined in the
       seed; identified by the digest's FE check);
    5. simply supported span ``l`` with overhang ``c``: point 1 in the span at ``a`` from the
       support away from the overhang, point 2 at the overhang tip:
       ``e11 = a^2 b^2/(3l)``, ``e22 = c^2 (l + c)/3``, ``e12 = -a b c (l + a)/(6l)``;
    6. clamped (0) - pinned (l) with overhang ``c``: ``e11`` as row 3,
       ``e22 = c^3/3 (1 + 3l/(4c))``, ``e12 = -c a^2/2 [3/2 (1 - a/(3l)) - 1]``.

    All values are divided by ``EI``.
    """
    b, d = l - a, l - c
    if case == 1:
        e = (a**3 / 3.0, c**3 / 3.0, a**2 / 2.0 * (c - a / 3.0))
    elif case == 2:
        e = (a**2 * b**2 / (3.0 * l), c**2 * d**2 / (3.0 * l),
             a * d / (6.0 * l) * (l**2 - a**2 - d**2))
    elif case == 3:
        e = _clamped_pinned_e11(l, a), _clamped_pinned_e11(l, c), \
            a**2 / 2.0 * (c - a / 3.0 - 3.0 * c**2 / (2.0 * l**3) * (l - a / 3.0) * (l - c / 3.0))
    elif case == 4:
        f = c - a
        e = (a**3 * b**3 / (3.0 * l**3), c**3 * d**3 / (3.0 * l**3),
             a * d / (6.0 * l**3) * (b * c * (l * f + 2.0 * a * d) - l**2 * f**2))
    elif case == 5:
        e = (a**2 * b**2 / (3.0 * l), c**2 * (l + c) / 3.0, -a * b * c * (l + a) / (6.0 * l))
    elif case == 6:
        e = (_clamped_pinned_e11(l, a), c**3 / 3.0 * (1.0 + 3.0 * l / (4.0 * c)),
             -c * a**2 / 2.0 * (1.5 * (1.0 - a / (3.0 * l)) - 1.0))
    else:
        raise ValueError(f"case = {case!r} is not valid; allowed: 1, 2, 3, 4, 5, 6")
    return tuple(float(v / EI) for v in e)


def _clamped_pinned_e11(l: float, a: float) -> float:
    return a**3 / 3.0 * (1.0 - a * (2.0 * l + (l - a)) ** 2 / (4.0 * l**3))


def two_mass_frequencies(e11, e22, e12, m1, m2) -> tuple[np.ndarray, np.ndarray]:
    """Natural frequencies ``(k1, k2)`` and form coefficients ``(beta1, beta2)`` of (4.30).

    (4.31) is a quadratic in ``h = 1/k^2``: ``h^2 - (e11 m1 + e22 m2) h + (e11 e22 - e12^2) m1 m2
    = 0``; it is solved in closed form with the discriminant written as
    ``(e11 m1 - e22 m2)^2 + 4 e12^2 m1 m2`` and the small root from Vieta (no cancellation).
    ``beta_r = B_r/A_r`` from (4.32), using whichever of its two equal expressions has the larger
    denominator (``inf`` if the mode has ``A_r = 0``).
    """
    s = e11 * m1 + e22 * m2
    p = (e11 * e22 - e12**2) * m1 * m2
    root = np.sqrt((e11 * m1 - e22 * m2) ** 2 + 4.0 * e12**2 * m1 * m2)
    h_big = 0.5 * (s + root)
    h = np.array([h_big, p / h_big])
    k2 = 1.0 / h
    num1, den1 = 1.0 - e11 * m1 * k2, e12 * m2 * k2
    num2, den2 = e12 * m1 * k2, 1.0 - e22 * m2 * k2
    use1 = np.abs(den1) >= np.abs(den2)
    with np.errstate(divide="ignore", invalid="ignore"):
        beta = np.where(use1, num1 / den1, num2 / den2)
    return np.sqrt(k2), beta


def dunkerley_bound(e_diag, masses) -> float:
    """Dunkerley lower bound (4.40): ``k1 >= 1 / sqrt(sum_i e_ii m_i)``."""
    return float(1.0 / np.sqrt(np.dot(np.asarray(e_diag, float), np.asarray(masses, float))))
