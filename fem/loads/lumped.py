"""The load map of a lumped model file (:func:`lumped_loads`): named coordinates = every body and driver
(gear-driven bodies included), links = the [[spring]] and [[damper]] tables, gears = the [[gear]]
tables, held = the drivers, elements and applied loads as the builder made them."""
from __future__ import annotations

import math

import numpy as np

from discrete.loads import Coordinates, ElementSpec, LinkSpec, SourceSpec, build
from discrete.lumped import GROUND

from .names import link_name


def _dense(A) -> np.ndarray:
    return np.asarray(A.toarray() if hasattr(A, "toarray") else A, dtype=float)


def _named_g(names: list, between, ratios) -> np.ndarray:
    g = np.zeros(len(names))
    (a, b), (ra, rb) = between, ratios
    if a != GROUND:
        g[names.index(a)] -= ra
    if b != GROUND:
        g[names.index(b)] += rb
    return g


def lumped_loads(doc, lm, spec, system, *, extra_C=None, extra_H=None, hysteretic: bool = False, sources=None,
                 undamped: bool = False):
    """:class:`discrete.loads.DriveLoads` of a lumped file: ``lm`` its :class:`~discrete.lumped.LumpedModel`,
    ``spec`` its :class:`~discrete.nonsmooth.ProblemSpec` (elements and forces with their named
    vectors), ``system`` the solved linear system (the time domain's, with psi turned viscous, or the
    linear analyses'); ``extra_C`` / ``extra_H``: damping beyond the links in solved coordinates (None:
    ``system.C`` minus the links' damping)."""
    names = lm.names
    indep, T = lm.transformation()
    inertia = np.array([b.inertia for b in lm.bodies] + [d.inertia for d in lm.drivers])
    links = []
    for i, t in enumerate(doc.spring, 1):
        g = _named_g(names, t.between, t.ratios)
        h = t.k * 2 * t.psi / (4 * math.pi)
        links.append(LinkSpec(link_name("spring", i, t), "spring", g, k=t.k, c=t.c, h=h,
                              info={"between": list(t.between), "ratios": list(t.ratios)}))
    for i, t in enumerate(doc.damper, 1):
        g = _named_g(names, t.between, t.ratios)
        links.append(LinkSpec(link_name("damper", i, t), "damper", g, c=t.c,
                              info={"between": list(t.between), "ratios": list(t.ratios)}))
    if undamped:
        for ln in links:
            ln.c, ln.h = 0.0, 0.0
    K = sum((ln.k * np.outer(ln.g, ln.g) for ln in links), np.zeros((len(names), len(names))))
    C = sum((ln.c * np.outer(ln.g, ln.g) for ln in links), np.zeros((len(names), len(names))))
    H = sum((ln.h * np.outer(ln.g, ln.g) for ln in links), np.zeros((len(names), len(names))))
    if extra_C is None:
        extra_C = _dense(system.C) - T.T @ C @ T
        scale = max(float(np.max(np.abs(_dense(system.C)))) if system.C.nnz else 0.0, 1e-300)
        extra_C[np.abs(extra_C) <= 1e-14 * scale] = 0.0
    gears = [(link_name("gear", i, t), names.index(t.between[0]), names.index(t.between[1]), t.ratio)
             for i, t in enumerate(doc.gear, 1)]
    held = [(d.name, "driver", names.index(d.name)) for d in lm.drivers]
    rates = np.array([b.inertia_rate for b in lm.bodies] + [0.0] * len(lm.drivers))
    react = np.array([b.reactive * b.inertia_rate for b in lm.bodies] + [0.0] * len(lm.drivers))
    variable = bool(np.any(rates)) and system is spec.system         # the time domain only
    coords = Coordinates(names=names, T=T, solved=[names.index(n) for n in indep], M=np.diag(inertia),
                         C=C + (np.diag(react) if variable else 0.0), K=K, H=H, extra_C=extra_C, extra_H=extra_H,
                         gears=gears, held=held, Mdot=np.diag(rates) if variable else None)
    layout = spec.layout or {}
    elements = [ElementSpec(el, g, table, info=_element_info(table, el))
                for el, (table, g) in zip(spec.elements, layout.get("elements", []))]
    if sources is None:
        sources = [SourceSpec(n, g) for n, g in zip(layout.get("force_names", []), layout.get("forces", []))]
    else:
        sources = [SourceSpec(name, np.eye(len(names))[names.index(indep[j])]) for name, j in sources]
    return build(coords, links, elements, sources, hysteretic=hysteretic)


def _element_info(table: str, el) -> dict:
    return {"kind": el.kind}
