"""Cross-sections and materials of shaft/beam segments."""
from __future__ import annotations

import math
from dataclasses import dataclass

from discrete import checks
from discrete.errors import ModelError

SHAPES = ("explicit", "circle", "tube")
KAPPA = ((">", 0.0), ("<=", 1.5))
"""The range of a Timoshenko shear coefficient, as the model file's ``kappa`` / ``shear_coefficient``."""


@dataclass(frozen=True)
class Material:
    """Isotropic material: Young's modulus E, shear modulus G (Pa), density rho (kg/m^3)."""

    E: float
    G: float
    rho: float

    def __post_init__(self):
        for key, note in (("E", "Young's modulus, Pa"), ("G", "shear modulus, Pa")):
            object.__setattr__(self, key, checks.positive("[material]", key, getattr(self, key), note))
        # rho = 0: a massless shaft whose inertia is all in point attachments ([drive] models, closed forms)
        object.__setattr__(self, "rho", checks.non_negative("[material]", "rho", self.rho,
                                                            "density, kg/m^3; 0: a massless shaft"))

    @property
    def nu(self) -> float:
        return self.E / (2.0 * self.G) - 1.0

    @classmethod
    def with_nu(cls, E: float, nu: float, rho: float) -> "Material":
        """From Young's modulus and Poisson's ratio: G = E / (2 (1 + nu))."""
        E = checks.positive("[material]", "E", E, "Young's modulus, Pa")
        nu = checks.bounded("[material]", "nu", nu, (">", -1.0), ("<", 0.5), "Poisson's ratio")
        return cls(E=E, G=E / (2.0 * (1.0 + nu)), rho=rho)


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

    def __post_init__(self):
        where = "section"
        checks.choice(where, "shape", self.shape, SHAPES)
        for key, note in (("A", "area, m^2"), ("I", "second moment of area, m^4"), ("J", "torsion constant, m^4"),
                          ("Ip", "polar moment of area, m^4")):
            val = getattr(self, key)
            if isinstance(val, float) and math.isnan(val) and self.shape == "explicit":
                continue                      # unknown: an error where a physics needs it (need())
            object.__setattr__(self, key, checks.positive(where, key, val, note))
        object.__setattr__(self, "inner_to_outer", checks.bounded(where, "inner_to_outer", self.inner_to_outer,
                                                                  (">=", 0.0), ("<", 1.0), "di / d"))
        object.__setattr__(self, "kappa", checks.optional(checks.bounded, where, "kappa", self.kappa, *KAPPA,
                                                          "Timoshenko shear coefficient"))
        object.__setattr__(self, "d", checks.optional(checks.positive, where, "d", self.d, "diameter, m"))

    def shear_coefficient(self, nu: float) -> float | None:
        """Cowper's shear coefficient for solid or hollow circular sections (None for explicit)."""
        if self.kappa is not None:
            return self.kappa
        if self.shape == "explicit":
            return None
        m2 = self.inner_to_outer ** 2
        return 6 * (1 + nu) * (1 + m2) ** 2 / ((7 + 6 * nu) * (1 + m2) ** 2 + (20 + 12 * nu) * m2)

    @classmethod
    def circle(cls, d: float, kappa: float | None = None) -> "Section":
        """Solid circular section of diameter d (m)."""
        d = checks.positive("section", "d", d, "diameter, m")
        A, I = math.pi * d**2 / 4, math.pi * d**4 / 64
        return cls(A=A, I=I, J=2 * I, Ip=2 * I, shape="circle", d=d, kappa=kappa)

    @classmethod
    def tube(cls, d: float, di: float, kappa: float | None = None) -> "Section":
        """Hollow circular section, outer diameter d, inner di < d (m)."""
        d = checks.positive("section", "d", d, "outer diameter, m")
        di = checks.positive("section", "di", di, "inner diameter, m")
        if not di < d:
            raise ModelError("section", "di", di, f"an inner diameter smaller than d = {d}")
        A, I = math.pi * (d**2 - di**2) / 4, math.pi * (d**4 - di**4) / 64
        return cls(A=A, I=I, J=2 * I, Ip=2 * I, shape="tube", inner_to_outer=di / d, d=d, kappa=kappa)

    @classmethod
    def explicit(cls, A: float | None = None, I: float | None = None, J: float | None = None,
                 Ip: float | None = None, kappa: float | None = None) -> "Section":
        """Section constants given directly; the missing ones are unknown (NaN) and an error
        where a physics needs them; Ip defaults to J."""
        nan = math.nan
        if A is None and I is None and J is None and Ip is None:
            raise ModelError("section", "section", {}, "{ shape = 'circle', d }, { shape = 'tube', d, di } or "
                             "explicit { A, I, J } constants")
        return cls(A=nan if A is None else A, I=nan if I is None else I, J=nan if J is None else J,
                   Ip=(J if Ip is None else Ip) if (Ip is not None or J is not None) else nan, kappa=kappa)

    def need(self, attr: str, where: str, physics: str) -> float:
        val = getattr(self, attr)
        if val is None or not math.isfinite(val):
            raise ModelError(f"{where} section", attr, None, f"a positive number (needed for {physics})")
        return val
