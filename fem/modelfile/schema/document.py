"""The model file as a whole: one declared type per kind of file, composed of the shared tables.

Kinds (decided once, from the tables present, by :func:`detect_kind`):

* ``fe``: a shaft/rod/beam (``[[segment]]``) with linear analyses;
* ``lumped``: bodies, drivers, springs, gears (``[[body]]``/``[[driver]]``), with nonsmooth
  elements, time simulation and nonlinear steady states;
* ``hybrid``: FE segments plus lumped bodies and nonsmooth elements (``[[segment]]`` with any
  element, body, driver, force, ``[reduction]`` or ``[simulation]``);
* ``drive``: a drive of regular structure (``[drive]``);
* ``rotor``: a spinning shaft line on bearings (``[rotor]``) with complex modes, Campbell diagram
  and unbalance response.
"""

from typing import Annotated

from pydantic import Field, create_model, model_validator

from discrete.errors import ModelError

from .analysis import Analysis, BaseMotion, Damping, ForcedAnalysis, Load, Response
from .base import Table, rule
from .drive import Drive
from .elements import ELEMENT_TABLES, DistributedFriction, Force
from .fe import Material, ModelSettings, Point, Segment, Support
from .lumped import Body, Damper, Driver, Gear, Spring
from .output import Output
from .rotor import (CampbellTable, CriticalMapTable, RotorAnalysis, RotorTable, RubTable, RunUpTable, StabilityTable,
                    StaticTable, UnbalanceResponseTable, UnbalanceTable)
from .simulation import Constants, Initial, Reduction, Simulation
from .steady import Steady, Sweep
from .superelement import SuperElement
from .train import (CouplingTable, MeshTable, TrainAnalysis, TrainBodyTable, TrainDriverTable, TrainForced,
                    TrainForceTable, TrainParametric, TrainReduction, TrainShaftTable, TrainTable)


def _array(item):
    return Annotated[list[item], Field(default_factory=list)]


class ModelFileBase(Table):
    """Keys of every model file."""

    title: str = ""
    """Free text, shown in outputs."""


class FETables(Table):
    material: Material | None = None
    """[material]: defaults of every segment (E, G or nu, rho)."""
    model: ModelSettings
    """[model]: physics, theory, mass, order."""
    segment: Annotated[list[Segment], Field(min_length=1)]
    """[[segment]]: uniform pieces of shaft, consecutive from x = 0."""
    support: _array(Support)
    """[[support]]: clamped, pinned or spring supports at nodes."""
    point: _array(Point)
    """[[point]]: lumped masses, inertias and springs at nodes."""


class LinearTables(Table):
    analysis: Analysis | None = None
    """[analysis]: type = "modal" | "forced" and its settings."""
    damping: Damping | None = None
    """[damping]: global damping (rayleigh, modal, hysteretic, none, viscous)."""


class ExcitationTables(Table):
    load: _array(Load)
    """[[load]]: harmonic forces of the forced analysis."""
    base_motion: _array(BaseMotion)
    """[[base_motion]]: harmonic motion of held DOFs (kinematic excitation)."""
    response: _array(Response)
    """[[response]]: output DOFs of the forced analysis."""


class LumpedTables(Table):
    body: _array(Body)
    """[[body]]: lumped bodies (one coordinate each)."""
    driver: _array(Driver)
    """[[driver]]: prescribed motions."""
    spring: _array(Spring)
    """[[spring]]: linear springs (with optional parallel dashpots)."""
    damper: _array(Damper)
    """[[damper]]: viscous dampers."""
    output: _array(Output)
    """[[output]]: named outputs (default: every element's deflection and force, every reaction)."""


class TimeTables(Table):
    force: _array(Force)
    """[[force]]: external forces in time."""
    constants: Constants = Constants()
    """[constants]: g."""
    simulation: Simulation | None = None
    """[simulation]: time integration."""
    steady: Steady | None = None
    """[steady]: nonlinear amplitude-frequency curve (drivefem forced)."""
    sweep: Sweep | None = None
    """[sweep]: parameter map (drivefem sweep)."""


def _summary(name: str, cls) -> str:
    """``[[name]]: <first sentence of the table's docstring>``."""
    text = " ".join((cls.__doc__ or "").split()).removeprefix(f"``[[{name}]]``:").strip()
    return f"[[{name}]]: " + text.split(". ")[0].rstrip(".") + "."


ElementTables = create_model(
    "ElementTables", __base__=TimeTables,
    **{name: (list[cls], Field(default_factory=list, description=_summary(name, cls)))
       for name, cls in ELEMENT_TABLES.items()})
"""The element tables (one per registered element, :func:`.elements.element_table`) and the time tables."""


def _frequencies_rule(doc) -> None:
    """A linear forced analysis names exactly one frequency list; a nonlinear one ([steady]) none."""
    an = doc.analysis
    if not isinstance(an, ForcedAnalysis):
        return
    keys = an.frequency_keys
    waves = [i for i, t in enumerate(getattr(doc, "load", ()), 1) if t.waveform is not None]
    if an.period is not None:
        if getattr(doc, "steady", None) is not None:
            rule("analysis.period", an.period, "no period with a [steady] table (periodic loads are linear analysis)")
        if keys:
            rule("analysis." + keys[0], getattr(an, keys[0]), "no frequency list with period = .. (the frequencies "
                 "are the harmonics j 2 pi / period)")
        return
    if waves:
        rule(f"load.{waves[0]}.waveform", "a waveform", "[analysis] period = .. (s): a periodic load needs the period")
    if an.given("harmonics"):
        rule("analysis.harmonics", an.harmonics, "only with period = .. (periodic loads)")
    if getattr(doc, "steady", None) is not None:
        if keys:
            rule("analysis." + keys[0], getattr(an, keys[0]), "no frequency list with a [steady] table "
                 "(the curve's frequencies are [steady] omega or z)")
    elif len(keys) != 1:
        rule("analysis.frequencies_hz", keys or None, "exactly one of frequencies_hz = [..], omega_rad_s = [..], "
             "sweep_hz = { start, stop, points, spacing = 'linear' | 'log' }")


class FEFile(ModelFileBase, FETables, LinearTables, ExcitationTables):
    """An FE model file: a shaft, rod or beam with modal or harmonic analysis."""

    output: _array(Output)
    """[[output]]: named outputs (default: the section loads at the key stations and every support's reaction)."""

    @model_validator(mode="after")
    def _rules(self):
        _frequencies_rule(self)
        return self


class LumpedFile(ModelFileBase, LumpedTables, LinearTables, ExcitationTables, ElementTables):
    """A lumped model file: bodies, drivers, springs, dampers, gears and nonsmooth elements."""

    gear: _array(Gear)
    """[[gear]]: rigid transmissions x_b = ratio x_a."""

    @model_validator(mode="after")
    def _rules(self):
        _frequencies_rule(self)
        return self


class HybridFile(ModelFileBase, FETables, LumpedTables, LinearTables, ElementTables):
    """A hybrid model file: FE segments plus lumped bodies and nonsmooth elements."""

    distributed_friction: _array(DistributedFriction)
    """[[distributed_friction]]: dry friction along the member (seed 003)."""
    reduction: Reduction | None = None
    """[reduction]: modal reduction of the FE part."""
    initial: Initial = Initial()
    """[initial]: initial state of the FE field."""
    superelement: _array(SuperElement)
    """[[superelement]]: linear parts from matrix files joined to the shaft."""

    @model_validator(mode="after")
    def _rules(self):
        _frequencies_rule(self)
        return self


class DriveFile(ModelFileBase, LinearTables):
    """A drive of regular structure: [drive] with [analysis] and [damping]."""

    drive: Drive
    """[drive]: n identical mechanisms on a main shaft."""

    @model_validator(mode="after")
    def _no_period(self):
        an = self.analysis
        if isinstance(an, ForcedAnalysis) and an.period is not None:
            rule("analysis.period", an.period, "a frequency list (periodic loads with period = .. are an analysis of "
                 "FE and lumped files)")
        return self


class RotorFile(ModelFileBase):
    """A rotor: a spinning shaft line with discs and bearings; complex modes, Campbell diagram, unbalance response."""

    rotor: RotorTable
    """[rotor]: shaft segments, discs, bearings, pedestals, couplings, supports."""
    analysis: RotorAnalysis | None = None
    """[analysis]: the default command (type) and the complex modal analysis at a speed."""
    campbell: CampbellTable | None = None
    """[campbell]: speeds, modes and orders of the Campbell diagram (drivefem campbell)."""
    unbalance_response: UnbalanceResponseTable | None = None
    """[unbalance_response]: speeds and probes of the unbalance response (drivefem forced)."""
    unbalance: _array(UnbalanceTable)
    """[[unbalance]]: mass unbalances (drivefem forced, drivefem simulate)."""
    run_up: RunUpTable | None = None
    """[run_up]: speed ramp, method and reduction of the transient run (drivefem simulate)."""
    rub: _array(RubTable)
    """[[rub]]: radial clearances with contact and friction: rotor-stator rub, bearing clearance (drivefem simulate)."""
    static: StaticTable | None = None
    """[static]: gravity, speed and point loads of the static deflection (drivefem static)."""
    critical_map: CriticalMapTable | None = None
    """[critical_map]: stiffness range of the undamped critical speed map (drivefem critical-map)."""
    stability: StabilityTable | None = None
    """[stability]: speeds of the stability threshold and the API Level I screening (drivefem stability)."""
    output: _array(Output)
    """[[output]]: named outputs (default: the section loads at the key stations, every bearing's reaction)."""


class TrainFile(ModelFileBase):
    """A geared train: named FE shafts and rotors, bodies, gear meshes and couplings (docs/geared.md)."""

    train: TrainTable = TrainTable()
    """[train]: speed reference and operating speed."""
    shaft: _array(TrainShaftTable)
    """[[shaft]]: named shafts (FE tables or a rotor table nested)."""
    body: _array(TrainBodyTable)
    """[[body]]: rigid bodies turning about x."""
    mesh: _array(MeshTable)
    """[[mesh]]: gear pairs."""
    coupling: _array(CouplingTable)
    """[[coupling]]: couplings (springs, dampers, backlash, slip torque)."""
    driver: _array(TrainDriverTable)
    """[[driver]]: prescribed motions."""
    force: _array(TrainForceTable)
    """[[force]]: loads (constant, harmonic, torque ripple of an order)."""
    analysis: TrainAnalysis | None = None
    """[analysis]: the default command and the modal speed."""
    campbell: CampbellTable | None = None
    """[campbell]: Campbell diagram over the reference speed (drivefem campbell)."""
    forced: TrainForced | None = None
    """[forced]: linear response over speed to transmission error and torque ripple (drivefem forced)."""
    parametric: TrainParametric | None = None
    """[parametric]: Floquet chart of the mesh-stiffness variation (drivefem parametric)."""
    reduction: TrainReduction | None = None
    """[reduction]: Craig-Bampton per shaft for the time simulation and the steady states."""
    simulation: Simulation | None = None
    """[simulation]: time integration (drivefem simulate)."""
    constants: Constants = Constants()
    """[constants]: g."""
    steady: Steady | None = None
    """[steady]: nonlinear amplitude-frequency curve (drivefem forced)."""
    sweep: Sweep | None = None
    """[sweep]: parameter map (drivefem sweep)."""

    @model_validator(mode="after")
    def _members(self):
        if not self.shaft and not self.body:
            rule("shaft", [], "at least one [[shaft]] or [[body]]")
        if self.steady is not None and self.forced is not None:
            rule("forced", "given", "either [forced] (linear response over speed) or [steady] (the nonlinear "
                 "curve), the two meanings of drivefem forced")
        return self


KINDS = {"fe": FEFile, "lumped": LumpedFile, "hybrid": HybridFile, "drive": DriveFile, "rotor": RotorFile,
         "train": TrainFile}
TRAIN_MARKERS = ("train", "shaft", "mesh", "coupling")
"""Top-level tables of a train file (no other kind has them)."""
HYBRID_MARKERS = tuple(dict.fromkeys(("body", "driver", "spring", "damper", *ELEMENT_TABLES, "force",
                                      "distributed_friction", "reduction", "initial", "simulation", "steady",
                                      "sweep", "superelement")))
"""Tables that make a file with [[segment]]s hybrid: lumped parts, every element table of the
element registry (a new element needs no entry here), and the time/steady-state tables."""


def detect_kind(doc: dict) -> str:
    """The kind of a parsed model file, from the tables it has (decided once)."""
    if any(k in doc for k in TRAIN_MARKERS):
        return "train"
    if "rotor" in doc:
        return "rotor"
    if "drive" in doc:
        return "drive"
    if "segment" in doc:
        return "hybrid" if any(k in doc for k in HYBRID_MARKERS) else "fe"
    if "body" in doc or "driver" in doc:
        return "lumped"
    raise ModelError("model file", "segment", None, "at least one [[segment]] (FE or hybrid model), [[body]] "
                     "(lumped model), a [drive] table (drive of regular structure), a [rotor] table (rotor on bearings) "
                     "or [[shaft]]/[[mesh]] tables (geared train)")


#: where a top-level key belongs, for the error of a key given in a file of another kind
OTHER_KIND = {
    **{k: "an FE table: only together with [[segment]] tables (FE or hybrid models)"
       for k in ("material", "model", "support", "point", "reduction", "initial", "distributed_friction",
                 "superelement")},
    **{k: "a table of FE and lumped models, not of drive files" for k in
       ("segment", "body", "driver", "spring", "damper", "gear", "friction", "one_sided", "gap", "impact",
        "cubic_spring", "force", "load", "base_motion", "response", "simulation", "steady", "sweep", "constants")},
    "gear": "a lumped-model table ([[gear]] is eliminated exactly in lumped models; not in FE/hybrid files)",
    "constants": "a table of time simulations (lumped or hybrid models)",
    "drive": "the table of a drive file ([drive] files have only [drive], [analysis], [damping] and title)",
}
HINTS = {
    "fe": {"constants": OTHER_KIND["constants"], "drive": OTHER_KIND["drive"], "gear": OTHER_KIND["gear"]},
    "lumped": {k: v for k, v in OTHER_KIND.items() if v.startswith("an FE table") or k == "drive"},
    "hybrid": {"gear": OTHER_KIND["gear"], "drive": OTHER_KIND["drive"],
               **{k: "a table of the linear forced analysis of FE and lumped models, not of hybrid files"
                  for k in ("load", "base_motion", "response")}},
    "drive": {k: v for k, v in OTHER_KIND.items() if k != "drive"},
    "rotor": {**{k: "not a table of rotor files (a [rotor] file has [rotor], [analysis], [campbell], "
                 "[unbalance_response], [[unbalance]], [run_up], [[rub]], [static], [critical_map], [stability], [[output]] and title)" for k in OTHER_KIND},
              "simulation": "in a rotor file the transient run is [run_up] (with [[rub]] clearances)",
              "material": "in a rotor file the shaft material is [rotor.material]",
              "segment": "in a rotor file the shaft pieces are [[rotor.segment]]",
              "support": "in a rotor file rigid supports are [[rotor.support]]"},
    "train": {**{k: "not a table of train files (a train file has [train], [[shaft]], [[body]], [[mesh]], "
                 "[[coupling]], [[driver]], [[force]], [analysis], [campbell], [forced], [parametric], [reduction], "
                 "[simulation], [constants], [steady], [sweep] and title)" for k in OTHER_KIND},
              "segment": "in a train file the FE segments belong to a shaft: [[shaft.segment]]",
              "material": "in a train file the material belongs to a shaft: [shaft.material]",
              "model": "in a train file the FE settings belong to a shaft: [shaft.model]",
              "support": "in a train file supports belong to a shaft: [[shaft.support]]",
              "point": "in a train file point attachments belong to a shaft: [[shaft.point]]",
              "rotor": "in a train file a rotor is a shaft: [[shaft]] with [shaft.rotor]",
              "gear": "in a train file gears are [[mesh]] tables (with stiffness, backlash, ...)",
              "gap": "in a train file backlash is a key of [[mesh]] or [[coupling]] (backlash = ..)",
              "friction": "in a train file a slipping joint is a [[coupling]] with slip_torque = ..",
              **{k: "not a table of train files" for k in ("load", "base_motion", "response", "damping", "initial",
                                                             "distributed_friction", "spring", "damper", "one_sided",
                                                             "impact", "cubic_spring", "contact", "motor",
                                                             "unbalance", "unbalance_response", "run_up", "rub",
                                                             "drive")}},
}
