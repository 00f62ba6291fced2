"""``[drive]`` -> :class:`fem.drives.DriveModel` (a drive of regular structure, textbook ch. 10)."""
from __future__ import annotations

from dataclasses import replace

from ...drives.model import DistributedShaft, DriveModel, LumpedShaft, Mechanism
from ..schema import drive as S


def drive_model(doc) -> DriveModel:
    d = doc.drive
    sh = d.shaft
    if isinstance(sh, S.LumpedDriveShaft):
        shaft = LumpedShaft(c0=sh.c0, J0=sh.J0)
    else:
        shaft = DistributedShaft(length=sh.length, GI=sh.GI, rho=sh.rho, J0=sh.J0, elements=sh.elements,
                                 order=sh.order, mass=sh.mass)
    me = d.mechanism
    c = me.c if me.c is not None else me.m * me.k ** 2
    co = d.continuum
    model = DriveModel(n=d.n, shaft=shaft, mechanism=Mechanism(m=me.m, c=c, ratio=me.ratio, output=me.output),
                       boundary=d.boundary, representation=d.representation,
                       force=d.load.force if d.load is not None else 0.0, continuum_elements=co.elements,
                       continuum_order=co.order, title=doc.title)
    if co.length is not None:            # the file gives the whole length; the model keeps it per segment
        model = replace(model, continuum_length=co.length / model.n_segments)
    return model
