"""Small model builders shared by the validation cases (uniform shafts and beams)."""
from __future__ import annotations

from fem import Material, PointAttachment, Section, Segment, ShaftModel, Support

STEEL = Material(E=2.1e11, G=8.1e10, rho=7850.0)


def uniform(physics: str, length: float, elements: int, *, d: float = 0.05, supports=(), points=(),
            theory: str = "euler-bernoulli", order: int = 2, mass: str = "consistent",
            material: Material = STEEL, section: Section | None = None, rho_extra: float = 0.0) -> ShaftModel:
    """A uniform circular shaft/beam; ``supports`` as (x, type) or (x, type, k, kr) tuples,
    ``points`` as PointAttachment or dicts."""
    sec = section or Section.circle(d)
    sups = [Support(*s) for s in supports]
    pts = [p if isinstance(p, PointAttachment) else PointAttachment(**p) for p in points]
    return ShaftModel(physics=physics, segments=[Segment(length, elements, sec, material, rho_extra=rho_extra)],
                      supports=sups, points=pts, theory=theory, order=order, mass=mass)


def unit_section(EI_or_GJ: float = 1.0, inertia: float = 1.0) -> tuple[Material, Section]:
    """Material/section giving stiffness 1 and inertia per length 1 for any physics
    (E = G = stiffness, rho = inertia, A = I = J = Ip = 1)."""
    mat = Material(E=EI_or_GJ, G=EI_or_GJ, rho=inertia)
    sec = Section(A=1.0, I=1.0, J=1.0, Ip=1.0)
    return mat, sec
