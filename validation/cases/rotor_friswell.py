"""Friswell, Penny, Garvey & Lees, *Dynamics of Rotating Machines* (Cambridge 2010), Example 5.9.1,
mesh for mesh; and the critical speeds of its variants by two independent methods."""
from __future__ import annotations

import numpy as np

from fem.rotor import (Bearing, Disc, Rotor, ShaftSegment, campbell, rotor_modes, rpm, undamped_critical_speeds)
from fem.sections import Material
from validation.analytic import rotor as ref
from validation.registry import case, check, claim, printed

SRC = "Friswell et al. (2010), Example 5.9.1"
STEEL = Material(E=211e9, G=81.2e9, rho=7810.0)


def friswell_591(elements: int = 6, dofs: str = "lateral", **bearing) -> Rotor:
    """Example 5.9.1: steel shaft 1.5 m, 50 mm, discs (70 mm thick, bore 50 mm) of 280 mm at 0.5 m and
    350 mm at 1.0 m, short bearings of 1 MN/m at both ends (``bearing`` overrides the coefficients)."""
    kw = {"kyy": 1e6, "kzz": 1e6, **bearing}
    return Rotor([ShaftSegment(1.5, elements, 0.05, STEEL)],
                 discs=[Disc.from_geometry(0.5, 0.07, 0.28, 0.05, STEEL.rho, "disc 1"),
                        Disc.from_geometry(1.0, 0.07, 0.35, 0.05, STEEL.rho, "disc 2")],
                 bearings=[Bearing(0.0, **kw), Bearing(1.5, **kw)], dofs=dofs)


@case("rotor-friswell-5-9-1", group="rotor")
def friswell():
    """6 Timoshenko elements of 0.25 m (shear, rotary inertia, consistent gyroscopic matrices;
    Cowper's kappa), 4000 rev/min: the five lowest lateral damped natural frequencies 85.39,
    87.80, 251.78, 294.71, 600.18 rad/s and, with axial and torsional DOFs, the torsional mode
    650.41 rad/s, each to half a unit of the printed digit.  Claims: the split pairs are
    backward (lower) then forward (upper) whirl; the axial and torsional motions (not held by
    the bearings) appear as rigid-body modes and the torsional mode is classified 'torsion'."""
    name = "rotor-friswell-5-9-1"
    out = []
    m = rotor_modes(friswell_591(6, "full"), rpm(4000), 10)
    elastic = ~m.rigid
    lat = m.omega_damped_rad_s[elastic & np.array([k == "lateral" for k in m.kind])]
    tor = m.omega_damped_rad_s[elastic & np.array([k == "torsion" for k in m.kind])]
    for j, txt in enumerate(ref.FRISWELL_5_9_1_LATERAL):
        val, tol = printed(txt)
        out.append(check(name, SRC, f"lateral w_{j + 1} at 4000 rev/min [rad/s]", val, lat[j], tol))
    val, tol = printed(ref.FRISWELL_5_9_1_TORSION)
    out.append(check(name, SRC, "torsional w at 4000 rev/min [rad/s]", val, tor[0] if tor.size else np.nan, tol))
    whirl = [w for w, k, r in zip(m.whirl, m.kind, m.rigid) if k == "lateral" and not r][:5]
    out.append(claim(name, SRC, "whirl of the lateral modes: backward, forward, backward, forward, backward",
                     whirl == ["backward", "forward", "backward", "forward", "backward"], note=", ".join(whirl)))
    out.append(claim(name, SRC, "axial and torsional rigid-body modes (free in the bearings) reported, not a crash",
                     int(m.rigid.sum()) == 2, note=f"{int(m.rigid.sum())} rigid"))
    out.append(claim(name, "modal solver", "all residuals below 1e-10", bool(np.all(m.residuals < 1e-10)),
                     note=f"max {m.residuals.max():.1e}"))
    return out


@case("rotor-critical-speeds-two-methods", group="rotor")
def critical_two_methods():
    """Critical speeds (orders 1 and 2) of the undamped Friswell rotor, isotropic and anisotropic
    (5.9.2: 1 and 0.8 MN/m) bearings, 6 elements as in the book, found twice: as roots of omega_j(Omega) = k Omega
    of the MAC-tracked Campbell diagram (Brent's method, converged to 1e-10) and as the positive
    eigenvalues Omega^2 of the linear problem K phi = Omega^2 (k^2 M - i k G) phi, which needs no
    tracking and no root finding.  Tolerance 1e-8 (measured ~1e-10)."""
    name = "rotor-critical-speeds-two-methods"
    out = []
    for tag, kw in (("isotropic", {}), ("anisotropic 5.9.2", {"kzz": 0.8e6})):
        rotor = friswell_591(6, **kw)
        camp = campbell(rotor, np.linspace(0.0, rpm(5000), 17), 8, orders=(1.0, 2.0))
        for k in (1.0, 2.0):
            roots = np.sort([c.speed_rad_s for c in camp.crossings if c.order == k])
            lin = undamped_critical_speeds(rotor, 8, order=k).speeds_rad_s
            lin = lin[lin <= rpm(5000)]
            out.append(claim(name, "two methods", f"{tag}, order {k:g}: same number of critical speeds below 5000 rev/min",
                             roots.size == lin.size, note=f"roots {roots.size}, linear problem {lin.size}"))
            for j in range(min(roots.size, lin.size)):
                out.append(check(name, "linear eigenproblem K phi = W^2 (k^2 M - i k G) phi",
                                 f"{tag}, order {k:g}, critical speed {j + 1} [rad/s]", lin[j], roots[j], 1e-8))
    return out
