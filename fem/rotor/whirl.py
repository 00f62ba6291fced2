"""Orbits and whirl direction of complex lateral amplitudes.

A node moving as v = Re(V e^{i w t}), w = Re(W e^{i w t}) (w > 0) traces an ellipse.  With the
complex position r = v + i w it is the sum of two circles,

    r(t) = F e^{i w t} + B e^{-i w t},   F = (V + i W) / 2,   B = (conj(V) + i conj(W)) / 2,

F turning from +y towards +z (the sense of the spin about +x: *forward*) and B the other way
(*backward*).  Semi-axes |F| + |B| and ||F| - |B||; the major axis points at (arg F + arg B) / 2;
the orbit runs forward when |F| > |B|.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: a node whose orbit is smaller than this fraction of the largest does not vote on the whirl
SIGNIFICANT = 1e-2
#: |whirl ratio| below this at every node: a straight-line (planar) orbit
PLANAR = 1e-6


@dataclass
class Orbits:
    """Ellipses of complex amplitudes V, W (arrays of the same shape)."""

    forward: np.ndarray          # |F|
    backward: np.ndarray         # |B|
    angle: np.ndarray            # direction of the major axis from +y towards +z, rad

    @classmethod
    def of(cls, V, W) -> "Orbits":
        V, W = np.asarray(V, dtype=complex), np.asarray(W, dtype=complex)
        F = 0.5 * (V + 1j * W)
        B = 0.5 * (np.conj(V) + 1j * np.conj(W))
        return cls(forward=np.abs(F), backward=np.abs(B), angle=0.5 * (np.angle(F) + np.angle(B)))

    @property
    def major(self) -> np.ndarray:
        return self.forward + self.backward

    @property
    def minor(self) -> np.ndarray:
        return np.abs(self.forward - self.backward)

    @property
    def ratio(self) -> np.ndarray:
        """(|F|^2 - |B|^2) / (|F|^2 + |B|^2) in [-1, 1]: +1 forward circle, -1 backward circle, 0 a line."""
        f2, b2 = self.forward**2, self.backward**2
        s = f2 + b2
        return np.where(s > 0, (f2 - b2) / np.where(s > 0, s, 1.0), 0.0)


def classify(V: np.ndarray, W: np.ndarray) -> tuple[str, float]:
    """Whirl of one mode from its nodal amplitudes V, W (1D over the shaft nodes):
    ("forward" | "backward" | "mixed" | "planar", overall ratio weighted by orbit size).

    forward/backward: every node whose orbit exceeds ``SIGNIFICANT`` of the largest whirls that
    way; mixed: some forward and some backward; planar: straight-line orbits (a repeated
    frequency at zero speed, whose pair can be combined into any orbit)."""
    return classify_orbits(Orbits.of(V, W))


def classify_orbits(o: Orbits) -> tuple[str, float]:
    """:func:`classify` of one mode's orbits (1D over the shaft nodes)."""
    size = o.major
    if not np.any(size > 0):
        return "none", 0.0
    big = size > SIGNIFICANT * size.max()
    r = o.ratio[big]
    f2, b2 = o.forward**2, o.backward**2
    overall = float((f2.sum() - b2.sum()) / (f2.sum() + b2.sum()))
    if np.all(np.abs(r) < PLANAR):
        return "planar", overall
    if np.all(r > 0):
        return "forward", overall
    if np.all(r < 0):
        return "backward", overall
    return "mixed", overall


def classify_many(o: Orbits) -> tuple[list, np.ndarray]:
    """:func:`classify_orbits` of every row of 2D orbits (modes x nodes) at once: (labels, overall
    ratios); the same arithmetic row by row (each row's sums reduce its own contiguous row)."""
    F, B = np.ascontiguousarray(o.forward), np.ascontiguousarray(o.backward)
    size = F + B
    top = size.max(axis=1, initial=0.0)
    big = size > SIGNIFICANT * top[:, None]
    ratio = Orbits(F, B, o.angle).ratio
    f2, b2 = F**2, B**2
    fs, bs = f2.sum(axis=1), b2.sum(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        overall = (fs - bs) / (fs + bs)
    labels = []
    for j in range(F.shape[0]):
        if not top[j] > 0:
            labels.append("none")
            overall[j] = 0.0
            continue
        r = ratio[j][big[j]]
        labels.append("planar" if np.all(np.abs(r) < PLANAR) else "forward" if np.all(r > 0)
                      else "backward" if np.all(r < 0) else "mixed")
    return labels, overall


def mac(A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """Modal assurance criterion |a^H b|^2 / ((a^H a)(b^H b)) between the columns of A and B."""
    num = np.abs(A.conj().T @ B) ** 2
    den = np.outer(np.einsum("ij,ij->j", A.conj(), A).real, np.einsum("ij,ij->j", B.conj(), B).real)
    return num / np.where(den > 0, den, 1.0)
