"""Squeeze-film dampers (:mod:`fem.rotor.bearings.squeeze_film`) against the classic closed forms and
the finite-element film."""
from __future__ import annotations

import math

import numpy as np

from fem.rotor.bearings.reynolds import ReynoldsFilm
from fem.rotor.bearings.squeeze_film import SqueezeFilmDamper
from validation.analytic import bearings as ref
from validation.registry import case, check

D, L, C, MU, W = 0.1, 0.01, 1e-4, 0.02, 300.0


@case("bearing-squeeze-film-damper", group="bearings")
def squeeze_film():
    """A short squeeze-film damper (D = 100 mm, L = 10 mm, c = 100 um, 0.02 Pa s) on circular centred
    orbits (eccentricity ratio 0.1, 0.5, 0.8, whirl 300 rad/s): the damper's film force (the
    short-bearing pressure at rest, integrated in closed form over the pressurised arc) against the
    classic closed forms of the pi and 2pi films (San Andres 2010; Vance 1988) to 1e-12 (two closed
    forms of one integral: round-off); the linear damping at the centre against pi mu R L^3 / c^3
    (2pi film) and half of it (pi film) to 1e-8 (central differences); and the short film against
    the finite-element film (Guembel's condition at rest, L/D = 1/10, 144 x 16 elements) within 3 %:
    the short bearing's (L/D)^2 error (measured 2.2 % in the radial force at eps = 0.5)."""
    name = "bearing-squeeze-film-damper"
    out = []
    R = D / 2
    for film in ("pi", "2pi"):
        d = SqueezeFilmDamper(0.0, diameter=D, length=L, clearance=C, viscosity=MU, film=film, centering_stiffness=1e6)
        scale = MU * R * L ** 3 * W / C ** 2
        for eps in (0.1, 0.5, 0.8):
            F = d.film_force(eps * C, 0.0, 0.0, eps * C * W)
            Fr, Ft = ref.damper_cco_forces(eps, film)
            src = f"{film} film on a circular centred orbit (closed form)"
            out.append(check(name, src, f"{film} film, eps = {eps:g}: radial force [N]", Fr * scale, F[0], 1e-12,
                             scale=abs(Ft * scale)))
            out.append(check(name, src, f"{film} film, eps = {eps:g}: tangential force [N]", Ft * scale, F[1], 1e-12))
        c_ref = math.pi * MU * R * L ** 3 / C ** 3 * (0.5 if film == "pi" else 1.0)
        out.append(check(name, "pi mu R L^3 / c^3 (2pi film; half for the pi film)", f"{film} film: damping at the "
                         "centre [N s/m]", c_ref, d.table()["cyy"][0], 1e-8))
    fe = ReynoldsFilm(L / D, 144, 16, "gumbel")
    eps = 0.5
    f_fe = fe.force(eps, 0.0, 12 * eps * W, 0.0) * MU * R ** 4 / C ** 2
    f_short = SqueezeFilmDamper(0.0, diameter=D, length=L, clearance=C, viscosity=MU).film_force(eps * C, 0.0, 0.0,
                                                                                              eps * C * W)
    out.append(check(name, "finite-element film at rest (Guembel), L/D = 1/10", "eps = 0.5: |F| [N]",
                     float(np.hypot(*f_fe)), float(np.hypot(*f_short)), 0.03))
    return out
