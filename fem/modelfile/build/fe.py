"""FE part of a model file -> :class:`fem.model.ShaftModel` (merging segment materials into
``[material]``; the model's own checks give the positional rules, as for Python users)."""
from __future__ import annotations

from discrete.errors import ModelError

from ...model import PointAttachment, Segment, ShaftModel, Support
from ...sections import Material, Section
from ..schema import fe as S


def material(table: S.Material | None, where: str, base: Material | None = None) -> Material | None:
    """A :class:`Material` from a table whose missing keys come from ``base``."""
    if table is None:
        return base
    E = table.E if table.E is not None else (base.E if base else None)
    rho = table.rho if table.rho is not None else (base.rho if base else None)
    if table.G is not None:
        G = table.G
    elif table.nu is not None:
        if E is None:
            raise ModelError(where, "E", None, "E must be given with nu")
        G = E / (2.0 * (1.0 + table.nu))
    else:
        G = base.G if base else None
    for key, val in (("E", E), ("G", G), ("rho", rho)):
        if val is None:
            raise ModelError(where, key, None, "a positive number (in [material] or in the segment)")
    return Material(E=E, G=G, rho=rho)


def section(table) -> Section:
    if isinstance(table, S.CircleSection):
        return Section.circle(table.d, kappa=table.kappa)
    if isinstance(table, S.TubeSection):
        return Section.tube(table.d, table.di, kappa=table.kappa)
    return Section.explicit(A=table.A, I=table.I, J=table.J, Ip=table.Ip, kappa=table.kappa)


def shaft_model(doc) -> ShaftModel:
    """The shaft of an FE or hybrid model file."""
    base = material(doc.material, "[material]") if doc.material is not None else None
    segments = []
    for i, t in enumerate(doc.segment, 1):
        w = f"[[segment]] #{i}"
        mat = material(t.material, f"{w} material", base)
        if mat is None:
            raise ModelError(w, "material", None, "a [material] table or a material override in the segment")
        segments.append(Segment(length=t.length, elements=t.elements, section=section(t.section), material=mat,
                                rho_extra=t.rho_extra, psi=t.psi))
    m = doc.model
    return ShaftModel(physics=m.physics, segments=segments,
                      supports=[Support(x=s.x, type=s.type, k=s.k, kr=s.kr) for s in doc.support],
                      points=[PointAttachment(x=p.x, mass=p.mass, inertia=p.inertia, k=p.k, kr=p.kr) for p in doc.point],
                      theory=m.theory, mass=m.mass, order=m.order, shear_coefficient=m.shear_coefficient,
                      title=doc.title)
