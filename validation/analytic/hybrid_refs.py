"""Independent references for the hybrid validation cases (issue 4).

* Elastic bar hitting a rigid wall (d'Alembert wave solution): the compression wave started at
  the contact travels to the free end and back, so contact lasts 2L/c; the wall force is
  rho c S v0 throughout; after separation the bar moves rigidly at -v0 (no residual vibration).
* Seed 003 (Pozhalostin & Panshina 2012), equivalent viscous damping of distributed dry friction:
  for the i-th mode X_i with modal mass m = int m0 X^2, stiffness k = int G0 X'^2 (X'' for
  bending), generalised force F = F0 X(x_j), friction intensity q = f P / l, the dry friction
  dissipates 4 A int q |X| dx per period; the equivalent viscous coefficient (equal work per
  period, (3)) is c_eq = 4 R / (pi p A) with R = int q |X| dx, and the forced amplitude (6)/(12) is

      A = sqrt(F^2 - (4 R / pi)^2) / |k - m p^2|,

  valid for small friction and motion without stops (it requires F > 4R/pi).  The OCR text of the
  seed's (6), (9), (12) is partly illegible; the structure A = sqrt(h^2 - b^2 (p/m)^2)/|omega^2 - p^2|
  (h = F/m, b p/m = 4R/(pi m)) is the seed's, the coefficients are re-derived here.
"""
from __future__ import annotations

import math

import numpy as np


def bar_wall(L: float, E: float, rho: float, A: float, v0: float) -> dict:
    c = math.sqrt(E / rho)
    return {"c": c, "duration": 2.0 * L / c, "force": rho * c * A * v0, "rebound_velocity": -v0}


def seed003_modes(example: str, l: float, stiffness: float, inertia: float, i: int = 1) -> dict:
    """Mode i of the seed's three examples: 'rod' (cantilever, longitudinal), 'shaft' (cantilever,
    torsion), 'beam' (simply supported, bending).  Returns the shape function X(x), omega,
    modal mass m = int inertia X^2 and stiffness k = m omega^2, int |X| dx."""
    if example in ("rod", "shaft"):
        lam = (2 * i - 1) * math.pi / (2 * l)
        X = lambda x: np.sin(lam * np.asarray(x))   # noqa: E731
        omega = lam * math.sqrt(stiffness / inertia)
        absint = 1.0 / lam if i == 1 else _abs_integral(X, l)    # int_0^l sin(lam x) dx = 1/lam
    elif example == "beam":
        lam = i * math.pi / l
        X = lambda x: np.sin(lam * np.asarray(x))   # noqa: E731
        omega = lam ** 2 * math.sqrt(stiffness / inertia)
        absint = 2.0 / lam if i == 1 else _abs_integral(X, l)
    else:
        raise ValueError(example)
    m = inertia * l / 2
    return {"X": X, "omega": omega, "m": m, "k": m * omega ** 2, "abs_integral": absint}


def _abs_integral(X, l: float, n: int = 200001) -> float:
    x = np.linspace(0, l, n)
    y = np.abs(X(x))
    return float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(x)))


def seed003_amplitude(m: float, k: float, p: float, F: float, R: float) -> float:
    """Equivalent-damping amplitude (6)/(12): sqrt(F^2 - (4R/pi)^2) / |k - m p^2| (nan if F <= 4R/pi)."""
    d = F ** 2 - (4 * R / math.pi) ** 2
    return math.sqrt(d) / abs(k - m * p ** 2) if d > 0 else float("nan")


def seed003_printed_factor(example: str, l: float = 1.0, i: int = 1) -> float:
    """R_printed / R of mode i: the seed replaces the friction's work 4 A int q |X_i| dx by the work of the
    i-th term of the friction's sine series, 4 A int a_i X_i dx, with a_i = 4 q/(pi (2i - 1)) (rod, shaft:
    X_i = sin((2i - 1) pi x/2l)) or 4 q/(i pi) for odd i (beam: X_i = sin(i pi x/l)) -- the step behind its
    printed (9).  Both integrals are evaluated here by quadrature; for i = 1 the ratio is 4/pi (the printed
    friction of the first mode is too large by 4/pi; for higher modes it is too small: 4/(pi (2i - 1)^2))."""
    from scipy.integrate import quad

    md = seed003_modes(example, l, 1.0, 1.0, i)
    if example in ("rod", "shaft"):
        a = 4.0 / (math.pi * (2 * i - 1))
    else:
        a = 4.0 / (i * math.pi) if i % 2 else 0.0
    X = md["X"]
    half_waves = (2 * i - 1) if example in ("rod", "shaft") else 2 * i
    pts = [l * k / half_waves for k in range(1, half_waves)]
    work = quad(lambda x: a * float(X(x)), 0, l, points=pts or None, epsabs=0, epsrel=1e-13, limit=200)[0]
    absw = quad(lambda x: abs(float(X(x))), 0, l, points=pts or None, epsabs=0, epsrel=1e-13, limit=200)[0]
    return work / absw
