"""The 1D mesh of a stepped shaft: segment ends and attachment points are always nodes."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from skfem import MeshLine

from .model import ShaftModel


@dataclass
class LineMesh:
    nodes: np.ndarray          # node coordinates, increasing
    elem_segment: np.ndarray   # segment index of every element

    @property
    def skfem(self) -> MeshLine:
        return MeshLine(self.nodes)

    @property
    def n_elements(self) -> int:
        return self.elem_segment.size


def build_line_mesh(model: ShaftModel) -> LineMesh:
    """Mesh every segment with its ``elements`` count; a support or point attachment that
    falls inside a segment splits it into pieces meshed in proportion to their lengths
    (at least one element each), so attachments sit exactly on nodes."""
    L = model.length
    tol = 1e-10 * L
    marks = np.array([p.x for p in model.points] + [s.x for s in model.supports], dtype=float)
    nodes, owner = [0.0], []
    x0 = 0.0
    for iseg, seg in enumerate(model.segments):
        x1 = x0 + seg.length
        inner = np.unique(marks[(marks > x0 + tol) & (marks < x1 - tol)])
        cuts = np.concatenate(([x0], inner, [x1]))
        pieces = np.diff(cuts)
        counts = np.maximum(1, np.round(seg.elements * pieces / seg.length).astype(int))
        for a, b, n in zip(cuts[:-1], cuts[1:], counts):
            nodes.extend(np.linspace(a, b, n + 1)[1:])
            owner.extend([iseg] * n)
        x0 = x1
    return LineMesh(nodes=np.asarray(nodes), elem_segment=np.asarray(owner, dtype=int))
