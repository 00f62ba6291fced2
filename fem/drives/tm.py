"""The transfer-matrix representation of a drive (§10.2): a chain of shaft members (lumped
springs c0, or exact continuous segments) and stations [disc J0, mechanism branch Pi'-c-m]."""
from __future__ import annotations

from discrete.transfer import Branch, Chain, Inertia, Ratio, Shaft, Spring

from .model import DistributedShaft, DriveModel


def build_chain(model: DriveModel, *, load: complex = 0.0, delta: float = 0.0) -> tuple[Chain, list[int], list[int]]:
    """(chain, index of each station's disc element, index of each mechanism branch element).
    ``delta``: hysteretic loss factor psi/(4 pi) on every elastic element (forced response)."""
    me = model.mechanism
    extra = me.m * me.ratio**2 if me.rigid else 0.0
    branch = None if me.rigid else Branch((Ratio(me.ratio), Spring(me.c, delta), Inertia(me.m)), end=me.output, load=load)
    if isinstance(model.shaft, DistributedShaft):
        sh = model.shaft
        member = Shaft(model.segment_length, sh.GI, sh.rho, delta)
        J0 = sh.J0 + extra
    else:
        member = Spring(model.shaft.c0, delta)
        J0 = model.shaft.J0 + extra
    els, discs, branches = [], [], []
    disc = Inertia(J0)          # one shared object per kind: the sweeps memoise identical elements
    for j in range(model.n):
        if j > 0 or model.start == "clamped":
            els.append(member)
        discs.append(len(els))
        els.append(disc)
        if branch is not None:
            branches.append(len(els))
            els.append(branch)
    if model.end == "clamped":
        els.append(member)
    return Chain(els, start=model.start, end=model.end), discs, branches
