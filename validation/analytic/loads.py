"""Exact internal loads of continuous shafts and beams (references of the ``loads-*`` validation cases).

Every solution is the exact solution of the continuous equations, propagated along x by the
transfer matrix expm(A x) of the first-order system (or its closed form), never by finite elements.
Sign convention of :mod:`fem.loads`: the section load at x is the action of the +x side on the -x
side; plane beams: shear V along +w, bending moment M conjugate to the slope (Euler-Bernoulli
M = E I w'', V = -E I w'''; Timoshenko M = E I phi', V = kappa G A (w' - phi)); torque T = G J theta'.
"""
from __future__ import annotations

import numpy as np
from scipy.linalg import expm


def torsion_transfer(GJ: float, inertia: float, omega: float, length: float) -> np.ndarray:
    """Transfer matrix of (theta, T) over a uniform shaft: theta'' = -(omega^2 inertia / GJ) theta, T = GJ theta'."""
    if omega == 0.0:
        return np.array([[1.0, length / GJ], [0.0, 1.0]])
    k = omega * np.sqrt(inertia / GJ)
    c, s = np.cos(k * length), np.sin(k * length)
    return np.array([[c, s / (GJ * k)], [-GJ * k * s, c]])


def stepped_torsion_torque(segments, discs: dict, end_torque: float, omega: float, x) -> tuple[np.ndarray, np.ndarray]:
    """Torque T(x) just left and just right of each x of a stepped shaft clamped at x = 0 and loaded by the
    harmonic end torque ``end_torque`` at its free end (amplitudes at ``omega`` rad/s, undamped).

    ``segments``: [(length, G J, rho I_p)] from x = 0; ``discs``: {x: polar inertia} at segment ends (the
    torque jumps by -omega^2 J_d theta there: J_d theta'' = T(x+) - T(x-)).  Exact wave solution per segment,
    matched: theta(0) = 0, T(L) = end_torque.  Returns (T(x-), T(x+))."""
    ends = np.concatenate(([0.0], np.cumsum([s[0] for s in segments])))

    def state(x_target, root_torque, side):
        y = np.array([0.0, root_torque])
        for (length, GJ, inertia), a in zip(segments, ends[:-1]):
            b = a + length
            if x_target <= a:
                break
            y = torsion_transfer(GJ, inertia, omega, min(b, x_target) - a) @ y
            if x_target < b or (x_target == b and side == "left"):
                return y
            J = discs.get(round(b, 12), 0.0)
            y = y + np.array([0.0, -omega**2 * J * y[0]])
        return y

    L = ends[-1]
    root = end_torque / state(L, 1.0, "left")[1]
    xs = np.atleast_1d(np.asarray(x, dtype=float))
    left = np.array([state(v, root, "left")[1] for v in xs])
    right = np.array([state(v, root, "right")[1] for v in xs])
    return left, right


def _propagate(A: np.ndarray, y0: np.ndarray, x) -> np.ndarray:
    return np.array([expm(A * v) @ y0 for v in np.atleast_1d(x)])


def euler_bernoulli_ss_harmonic(EI: float, rhoA: float, length: float, a: float, force: float, omega: float,
                                x) -> tuple[np.ndarray, np.ndarray]:
    """Bending moment M = E I w'' and shear V = -E I w''' of a simply supported uniform Euler-Bernoulli beam
    under the harmonic point force ``force`` (along +w) at x = a, undamped: E I w'''' - rho A omega^2 w = 0 on
    each side, w = w'' = 0 at both ends, w, w', w'' continuous at a and E I (w'''(a+) - w'''(a-)) = force
    (the shear drops by the force).  Values just right of each x (``V`` at x = a: V(a+))."""
    b4 = rhoA * omega**2 / EI
    A = np.zeros((4, 4))
    A[0, 1] = A[1, 2] = A[2, 3] = 1.0
    A[3, 0] = b4                                          # y = (w, w', w'', w'''), w'''' = b4 w
    jump = np.array([0.0, 0.0, 0.0, force / EI])
    Ea, Eb = expm(A * a), expm(A * (length - a))
    # unknowns w'(0), w'''(0): y(0) = P u
    P = np.zeros((4, 2))
    P[1, 0] = P[3, 1] = 1.0
    end = Eb @ Ea @ P                                     # y(L) = end u + Eb jump
    rows = [0, 2]
    u = np.linalg.solve(end[rows], -(Eb @ jump)[rows])
    y0 = P @ u
    xs = np.atleast_1d(np.asarray(x, dtype=float))
    ys = np.array([expm(A * v) @ y0 if v < a else expm(A * (v - a)) @ (Ea @ y0 + jump) for v in xs])
    return EI * ys[:, 2], -EI * ys[:, 3]


def timoshenko_cantilever_harmonic(EI: float, kGA: float, rhoA: float, rhoI: float, length: float, force: float,
                                   omega: float, x) -> tuple[np.ndarray, np.ndarray]:
    """Bending moment M = E I phi' and shear V = kappa G A (w' - phi) of a uniform Timoshenko cantilever
    (clamped at x = 0: w = phi = 0) under the harmonic tip force ``force`` (along +w) at x = L (M(L) = 0,
    V(L) = force), with translational and rotary inertia, undamped:

        kappa G A (w'' - phi') = -omega^2 rho A w,    E I phi'' = -kappa G A (w' - phi) - omega^2 rho I phi."""
    A = np.zeros((4, 4))                                  # y = (w, phi, w', phi')
    A[0, 2] = A[1, 3] = 1.0
    A[2, 0] = -omega**2 * rhoA / kGA
    A[2, 3] = 1.0
    A[3, 1] = (kGA - omega**2 * rhoI) / EI
    A[3, 2] = -kGA / EI
    EL = expm(A * length)
    P = np.zeros((4, 2))
    P[2, 0] = P[3, 1] = 1.0                               # unknowns w'(0), phi'(0)
    out = EL @ P
    rows = np.array([[0.0, 0.0, 0.0, EI], [0.0, -kGA, kGA, 0.0]]) @ out   # M(L), V(L)
    u = np.linalg.solve(rows, [0.0, force])
    y = _propagate(A, P @ u, x)
    return EI * y[:, 3], kGA * (y[:, 2] - y[:, 1])


def observed_order(h: np.ndarray, err: np.ndarray) -> float:
    """Least-squares slope of log(err) against log(h)."""
    return float(np.polyfit(np.log(h), np.log(err), 1)[0])
