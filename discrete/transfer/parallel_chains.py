"""Parallel connection of sub-chains between the same two sections (textbook (10.7)-(10.9))."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import ModelError
from .chain import Chain, count_below, element_matrix
from .elements import Damper, Member, Shaft, Spring, _arr


@dataclass(frozen=True, eq=False)
class Parallel(Member):
    """Member made of sub-chains connected in parallel between the same two sections (10.7)-(10.9).
    Each sub-chain (listed input -> output) needs an elastic element (B != 0).  Its dynamic
    stiffness is [[g1, -g2], [-g2, g3]] with g1 = sum A/B, g2 = sum 1/B, g3 = sum D/B; its
    clamped-end count is the sum of the sub-chains' clamped-clamped counts."""

    chains: tuple = field(default_factory=tuple)

    def __post_init__(self):
        object.__setattr__(self, "chains", tuple(tuple(c) for c in self.chains))
        if len(self.chains) < 2:
            raise ModelError("parallel", "chains", len(self.chains), "at least two sub-chains")
        for i, ch in enumerate(self.chains):
            if not any(isinstance(e, (Spring, Shaft, Damper)) for e in ch) or not isinstance(ch[-1], (Spring, Shaft, Damper)) \
                    or not isinstance(ch[0], (Spring, Shaft, Damper)):
                raise ModelError("parallel", f"chains[{i}]", [type(e).__name__ for e in ch],
                                 "a sub-chain that starts and ends with an elastic member (B != 0)")

    @property
    def real(self) -> bool:
        return all(getattr(e, "real", True) for ch in self.chains for e in ch)

    def _mats(self, p):
        p = np.atleast_1d(_arr(p))
        out = []
        for ch in self.chains:
            G = np.empty((p.size, 2, 2), dtype=complex if not self.real else float)
            for i, q in enumerate(p):
                M = np.eye(2)
                for e in ch:
                    M = element_matrix(e, q) @ M
                G[i] = M
            out.append(G)
        return out

    def _gammas(self, p):
        mats = self._mats(p)
        g1 = sum(G[:, 0, 0] / G[:, 0, 1] for G in mats)
        g2 = sum(1.0 / G[:, 0, 1] for G in mats)
        g3 = sum(G[:, 1, 1] / G[:, 0, 1] for G in mats)
        return g1, g2, g3

    def T(self, p):
        g1, g2, g3 = self._gammas(p)
        return g1 / g2, 1.0 / g2, (g1 * g3 - g2**2) / g2, g3 / g2

    def stiffness(self, p):
        g1, g2, g3 = self._gammas(p)
        return g1, -g2, g3

    def det_stiffness(self, p):
        g1, g2, g3 = self._gammas(p)
        return g1 * g3 - g2**2

    def count(self, p):
        return sum(count_below(Chain(list(ch), "clamped", "clamped"), p) for ch in self.chains)
