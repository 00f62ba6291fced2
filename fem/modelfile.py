"""Model file v1 (TOML, design.md §4): parsing into FE or lumped models and analysis settings.

Unknown keys are errors.  An FE model has ``[[segment]]`` tables, a lumped model ``[[body]]``
tables.  Linear analyses are set in ``[analysis]`` (``type = "modal" | "forced"``) with
``[damping]``, ``[[load]]``, ``[[base_motion]]`` and ``[[response]]`` for forced response.
"""
from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from discrete.errors import ModelError
from discrete.linear_system import LinearSystem
from discrete.lumped import LumpedModel
from discrete.schema import check_keys, choice, number

from .model import PointAttachment, Segment, ShaftModel, Support
from .sections import Material, Section

FE_KEYS = {"material", "model", "segment", "support", "point"}
LUMPED_KEYS = {"body", "driver", "spring", "damper", "gear"}
ANALYSIS_KEYS = {"title", "analysis", "damping", "load", "base_motion", "response", "constants", "simulation"}
BENDING_ONLY = {"theory": "theory applies only to physics = 'bending'",
                "shear_coefficient": "shear_coefficient applies only to Timoshenko bending models"}


def _nonsmooth_keys() -> set[str]:
    """Top-level keys of the time-simulation and steady-state tables (discrete.nonsmooth/steady)."""
    from discrete.nonsmooth import TOP_LEVEL_KEYS as simulation_keys
    from discrete.steady import TOP_LEVEL_KEYS as steady_keys

    return set(simulation_keys) | set(steady_keys)


@dataclass
class ModelFile:
    """A parsed model file: the model (FE or lumped) and the raw tables for the analyses."""

    doc: dict
    kind: str                                  # "fe" | "lumped"
    model: ShaftModel | LumpedModel
    path: Path | None = None
    _fe: object = field(default=None, repr=False)

    @property
    def title(self) -> str:
        return self.doc.get("title", "") or (self.path.stem if self.path else "")

    @property
    def analysis(self) -> dict:
        return self.doc.get("analysis", {})

    def fe_model(self):
        """The assembled :class:`fem.assembly.FEModel` (FE models only; assembled once)."""
        from .assembly import assemble

        if self.kind != "fe":
            raise ModelError("", "segment", None, "an FE model (with [[segment]] tables) for this operation")
        if self._fe is None:
            self._fe = assemble(self.model)
        return self._fe

    def linear_system(self) -> LinearSystem:
        return self.fe_model().system if self.kind == "fe" else self.model.linear_system()


def load_model_file(path: str | Path) -> ModelFile:
    path = Path(path)
    if not path.is_file():
        raise ModelError("", "model file", str(path), "an existing TOML file")
    try:
        with open(path, "rb") as fh:
            doc = tomllib.load(fh)
    except tomllib.TOMLDecodeError as exc:
        raise ModelError(str(path), "TOML", str(exc), "valid TOML syntax") from exc
    mf = parse_model(doc)
    mf.path = path
    return mf


def parse_model(doc: dict) -> ModelFile:
    allowed = FE_KEYS | LUMPED_KEYS | ANALYSIS_KEYS | _nonsmooth_keys() | {"reduction", "drive"}
    check_keys(doc, allowed, "model file (top level)")
    has_fe, has_lumped = "segment" in doc, "body" in doc
    if has_fe and has_lumped and "reduction" not in doc:
        raise ModelError("model file", "body", "...", "either [[segment]] (FE model) or [[body]] (lumped model); "
                         "hybrid models need a [reduction] table")
    if has_fe:
        return ModelFile(doc=doc, kind="fe", model=parse_shaft(doc))
    if has_lumped or "driver" in doc:
        bad = FE_KEYS & set(doc)
        if bad:
            key = sorted(bad)[0]
            raise ModelError("model file", key, "...", "FE tables only together with [[segment]]")
        return ModelFile(doc=doc, kind="lumped", model=LumpedModel.from_dict(doc))
    raise ModelError("model file", "segment", None, "at least one [[segment]] (FE model) or [[body]] (lumped model)")


def parse_shaft(doc: dict) -> ShaftModel:
    mat_doc = doc.get("material", {})
    base = Material.from_dict(mat_doc, "[material]") if mat_doc else None
    mdl = doc.get("model", {})
    where = "[model]"
    check_keys(mdl, {"physics", "theory", "mass", "order", "shear_coefficient"}, where)
    physics = choice(mdl.get("physics"), "physics", where, ("torsion", "axial", "bending"))
    if physics != "bending":
        for key in BENDING_ONLY:
            if key in mdl:
                raise ModelError(where, key, mdl[key], BENDING_ONLY[key] + f" (this model: physics = {physics!r})")
    theory = mdl.get("theory", "euler-bernoulli")
    if physics == "bending" and theory != "timoshenko" and "shear_coefficient" in mdl:
        raise ModelError(where, "shear_coefficient", mdl["shear_coefficient"], BENDING_ONLY["shear_coefficient"])
    order = mdl.get("order", 2)
    if physics == "bending" and theory == "euler-bernoulli" and "order" in mdl:
        raise ModelError(where, "order", order, "no order for Euler-Bernoulli beams (Hermite cubic elements)")
    segments = []
    for i, t in enumerate(doc.get("segment", []), 1):
        w = f"[[segment]] #{i}"
        check_keys(t, {"length", "elements", "section", "material", "rho_extra", "psi"}, w)
        if "section" not in t or not isinstance(t["section"], dict):
            raise ModelError(w, "section", t.get("section"), "a table, e.g. { shape = 'circle', d = 0.05 }")
        mat = Material.from_dict(t["material"], f"{w} material", base) if "material" in t else base
        if mat is None:
            raise ModelError(w, "material", None, "a [material] table or a material override in the segment")
        elements = t.get("elements")
        if isinstance(elements, bool) or not isinstance(elements, int) or elements < 1:
            raise ModelError(w, "elements", elements, "an integer >= 1")
        segments.append(Segment(length=number(t.get("length"), "length", w, positive=True), elements=elements,
                                section=Section.from_dict(t["section"], w), material=mat,
                                rho_extra=number(t.get("rho_extra", 0.0), "rho_extra", w, nonnegative=True),
                                psi=number(t.get("psi", 0.0), "psi", w, nonnegative=True)))
    supports = []
    for i, t in enumerate(doc.get("support", []), 1):
        w = f"[[support]] #{i}"
        check_keys(t, {"x", "type", "k", "kr"}, w)
        supports.append(Support(x=number(t.get("x"), "x", w), type=t.get("type", "clamped"),
                                k=number(t.get("k", 0.0), "k", w), kr=number(t.get("kr", 0.0), "kr", w)))
    points = []
    for i, t in enumerate(doc.get("point", []), 1):
        w = f"[[point]] #{i}"
        check_keys(t, {"x", "mass", "inertia", "k", "kr"}, w)
        points.append(PointAttachment(x=number(t.get("x"), "x", w),
                                      **{k: number(t.get(k, 0.0), k, w) for k in ("mass", "inertia", "k", "kr")}))
    kappa = mdl.get("shear_coefficient")
    return ShaftModel(physics=physics, segments=segments, supports=supports, points=points, theory=theory,
                      mass=mdl.get("mass", "consistent"), order=order,
                      shear_coefficient=None if kappa is None else number(kappa, "shear_coefficient", where, positive=True),
                      title=doc.get("title", ""))


# ------------------------------------------------------------------ analyses
@dataclass
class ForcedSpec:
    omegas: np.ndarray
    method: str
    n_modes: int | None
    force: np.ndarray
    base_motion: dict
    outputs: list[int]


def parse_damping(doc: dict):
    from discrete.linear.harmonic import Damping

    t = doc.get("damping", {})
    check_keys(t, {"type", "alpha", "beta", "zeta", "psi"}, "[damping]")
    vals = {k: number(t[k], k, "[damping]", nonnegative=True) for k in ("alpha", "beta", "zeta", "psi") if k in t}
    return Damping(type=t.get("type", "viscous"), **vals)


def _frequencies(an: dict) -> np.ndarray:
    where = "[analysis]"
    given = [k for k in ("frequencies_hz", "omega_rad_s", "sweep_hz") if k in an]
    if len(given) != 1:
        raise ModelError(where, "frequencies_hz", given or None,
                         "exactly one of frequencies_hz = [..], omega_rad_s = [..], "
                         "sweep_hz = { start, stop, points, spacing = 'linear' | 'log' }")
    key = given[0]
    if key == "sweep_hz":
        sw = an[key]
        check_keys(sw, {"start", "stop", "points", "spacing"}, f"{where} sweep_hz")
        start = number(sw.get("start"), "start", f"{where} sweep_hz", nonnegative=True)
        stop = number(sw.get("stop"), "stop", f"{where} sweep_hz", positive=True)
        pts = number(sw.get("points", 200), "points", f"{where} sweep_hz", positive=True, integer=True)
        spacing = choice(sw.get("spacing", "linear"), "spacing", f"{where} sweep_hz", ("linear", "log"))
        if not stop > start:
            raise ModelError(f"{where} sweep_hz", "stop", stop, f"a frequency above start = {start}")
        if spacing == "log" and start <= 0:
            raise ModelError(f"{where} sweep_hz", "start", start, "a frequency > 0 for spacing = 'log'")
        f = np.geomspace(start, stop, pts) if spacing == "log" else np.linspace(start, stop, pts)
        return 2 * np.pi * f
    vals = an[key]
    if not isinstance(vals, list) or not vals:
        raise ModelError(where, key, vals, "a non-empty list of numbers")
    arr = np.array([number(v, key, where, nonnegative=True) for v in vals])
    return 2 * np.pi * arr if key == "frequencies_hz" else arr


def _locate(system: LinearSystem, t: dict, where: str, kind: str) -> int:
    """DOF of a load/response/base-motion table: FE by x and dof, lumped by body/driver name."""
    if system.physics == "lumped":
        key = "driver" if kind == "base_motion" else "body"
        name = t.get(key)
        if name is None:
            raise ModelError(where, key, None, f"the name of a {key}")
        return system.dof_index(name=name, where=where)
    x = number(t.get("x"), "x", where)
    return system.dof_index(field=t.get("dof", system.dof_field[0]), x=x, where=where)


def parse_forced(mf: ModelFile, system: LinearSystem) -> ForcedSpec:
    an = mf.analysis
    where = "[analysis]"
    check_keys(an, {"type", "frequencies_hz", "omega_rad_s", "sweep_hz", "method", "modes"}, where)
    omegas = _frequencies(an)
    method = choice(an.get("method", "direct"), "method", where, ("direct", "modal"))
    n_modes = number(an["modes"], "modes", where, positive=True, integer=True) if "modes" in an else None
    keys_fe, keys_l = {"x", "dof", "amplitude", "phase_deg"}, {"body", "amplitude", "phase_deg"}
    force = np.zeros(system.n_dofs, dtype=complex)
    for i, t in enumerate(mf.doc.get("load", []), 1):
        w = f"[[load]] #{i}"
        check_keys(t, keys_l if system.physics == "lumped" else keys_fe, w)
        dof = _locate(system, t, w, "load")
        if dof in set(system.constrained.tolist()):
            raise ModelError(w, "x", t.get("x", t.get("body")), "a free DOF (this one is held by a support/driver)")
        force[dof] += number(t.get("amplitude"), "amplitude", w) * np.exp(1j * math.radians(number(t.get("phase_deg", 0.0), "phase_deg", w)))
    base = {}
    for i, t in enumerate(mf.doc.get("base_motion", []), 1):
        w = f"[[base_motion]] #{i}"
        check_keys(t, {"driver", "amplitude", "phase_deg"} if system.physics == "lumped" else keys_fe, w)
        dof = _locate(system, t, w, "base_motion")
        if dof not in set(system.constrained.tolist()):
            raise ModelError(w, "x" if system.physics != "lumped" else "driver", t.get("x", t.get("driver")),
                             "a held DOF: a clamped/pinned support (FE) or a driver (lumped)")
        base[dof] = number(t.get("amplitude"), "amplitude", w) * np.exp(1j * math.radians(number(t.get("phase_deg", 0.0), "phase_deg", w)))
    outputs = []
    for i, t in enumerate(mf.doc.get("response", []), 1):
        w = f"[[response]] #{i}"
        check_keys(t, {"body"} if system.physics == "lumped" else {"x", "dof"}, w)
        outputs.append(_locate(system, t, w, "response"))
    if not outputs:
        outputs = sorted(set(np.flatnonzero(force).tolist()))
    if not outputs:  # base motion only: every body, or the free end of the primary field
        if system.physics == "lumped":
            outputs = system.free.tolist()
        else:
            prim = system.free[system.dof_field[system.free] == system.dof_field[0]]
            outputs = [int(prim[np.argmax(np.abs(system.dof_x[prim] - system.dof_x[system.constrained].mean()))])]
    return ForcedSpec(omegas=omegas, method=method, n_modes=n_modes, force=force, base_motion=base, outputs=outputs)
