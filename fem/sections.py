"""Cross-sections and materials of shaft/beam segments."""
from __future__ import annotations

import math
from dataclasses import dataclass

from discrete.errors import ModelError
from discrete.schema import check_keys, number


@dataclass(frozen=True)
class Material:
    """Isotropic material: Young's modulus E, shear modulus G (Pa), density rho (kg/m^3)."""

    E: float
    G: float
    rho: float

    @property
    def nu(self) -> float:
        return self.E / (2.0 * self.G) - 1.0

    @classmethod
    def from_dict(cls, d: dict, where: str, base: "Material | None" = None) -> "Material":
        check_keys(d, {"E", "G", "nu", "rho"}, where)
        E = number(d["E"], "E", where, positive=True) if "E" in d else (base.E if base else None)
        rho = number(d["rho"], "rho", where, positive=True) if "rho" in d else (base.rho if base else None)
        if "G" in d and "nu" in d:
            raise ModelError(where, "nu", d["nu"], "either G or nu, not both")
        if "G" in d:
            G = number(d["G"], "G", where, positive=True)
        elif "nu" in d:
            nu = number(d["nu"], "nu", where)
            if not -1.0 < nu < 0.5:
                raise ModelError(where, "nu", nu, "a Poisson ratio in (-1, 0.5)")
            if E is None:
                raise ModelError(where, "E", None, "E must be given with nu")
            G = E / (2.0 * (1.0 + nu))
        else:
            G = base.G if base else None
        for key, val in (("E", E), ("G", G), ("rho", rho)):
            if val is None:
                raise ModelError(where, key, None, "a positive number (in [material] or in the segment)")
        return cls(E=E, G=G, rho=rho)


@dataclass(frozen=True)
class Section:
    """Section constants.

    A: area (m^2); I: second moment of area for bending (m^4); J: torsion constant (m^4);
    Ip: polar moment of area used for the rotary inertia rho*Ip of torsion (m^4; equals J
    for circular sections); kappa: Timoshenko shear coefficient (None: Cowper's value for
    circular sections, required for explicit sections in Timoshenko models).
    """

    A: float
    I: float
    J: float
    Ip: float
    shape: str = "explicit"
    inner_to_outer: float = 0.0
    kappa: float | None = None
    d: float | None = None

    def shear_coefficient(self, nu: float) -> float | None:
        """Cowper's shear coefficient for solid or hollow circular sections (None for explicit)."""
        if self.kappa is not None:
            return self.kappa
        if self.shape == "explicit":
            return None
        m2 = self.inner_to_outer ** 2
        return 6 * (1 + nu) * (1 + m2) ** 2 / ((7 + 6 * nu) * (1 + m2) ** 2 + (20 + 12 * nu) * m2)

    @classmethod
    def from_dict(cls, d: dict, where: str) -> "Section":
        where = f"{where} section"
        shape = d.get("shape", "explicit")
        if shape == "circle":
            check_keys(d, {"shape", "d", "kappa"}, where)
            dia = number(d.get("d"), "d", where, positive=True)
            A, I = math.pi * dia**2 / 4, math.pi * dia**4 / 64
            sec = cls(A=A, I=I, J=2 * I, Ip=2 * I, shape="circle", d=dia,
                      kappa=_opt_kappa(d, where))
        elif shape == "tube":
            check_keys(d, {"shape", "d", "di", "kappa"}, where)
            do = number(d.get("d"), "d", where, positive=True)
            di = number(d.get("di"), "di", where, positive=True)
            if not di < do:
                raise ModelError(where, "di", di, f"an inner diameter smaller than d = {do}")
            A, I = math.pi * (do**2 - di**2) / 4, math.pi * (do**4 - di**4) / 64
            sec = cls(A=A, I=I, J=2 * I, Ip=2 * I, shape="tube", inner_to_outer=di / do, d=do,
                      kappa=_opt_kappa(d, where))
        elif shape == "explicit":
            check_keys(d, {"shape", "A", "I", "J", "Ip", "kappa"}, where)
            vals = {k: number(d[k], k, where, positive=True) for k in ("A", "I", "J", "Ip") if k in d}
            if not vals:
                raise ModelError(where, "section", d, "{ shape = 'circle', d }, { shape = 'tube', d, di } "
                                 "or explicit { A, I, J } constants")
            sec = cls(A=vals.get("A", math.nan), I=vals.get("I", math.nan), J=vals.get("J", math.nan),
                      Ip=vals.get("Ip", vals.get("J", math.nan)), kappa=_opt_kappa(d, where))
        else:
            raise ModelError(where, "shape", shape, "'circle' | 'tube' | 'explicit' (or give A, I, J)")
        return sec

    def need(self, attr: str, where: str, physics: str) -> float:
        val = getattr(self, attr)
        if val is None or not math.isfinite(val):
            raise ModelError(f"{where} section", attr, None, f"a positive number (needed for {physics})")
        return val


def _opt_kappa(d: dict, where: str) -> float | None:
    if "kappa" not in d:
        return None
    k = number(d["kappa"], "kappa", where, positive=True)
    if k > 1.5:
        raise ModelError(where, "kappa", k, "a shear coefficient in (0, 1.5] (about 0.85-0.9 for solid shafts)")
    return k
