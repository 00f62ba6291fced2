"""Tables of a geared train file (kind ``train``, docs/geared.md): ``[train]``, ``[[shaft]]`` (an FE shaft:
the ``[model]``, ``[material]``, ``[[segment]]``, ``[[support]]``, ``[[point]]`` tables of FE files nested
verbatim; or a rotor: the ``[rotor]`` table of rotor files nested as ``[shaft.rotor]``), ``[[body]]``,
``[[mesh]]``, ``[[coupling]]``, ``[[driver]]``, ``[[force]]``, and the analyses ``[analysis]`` (modal at a
speed; the default command), ``[campbell]``, ``[forced]`` (linear response over speed), ``[parametric]``
(mesh-stiffness variation), ``[reduction]`` with ``[simulation]``, ``[steady]``, ``[sweep]``.

Angles are given in degrees (``*_deg``), speeds in rad/s or rev/min (one of the two), lengths in m.
An end of a connection (``between``) is a body name, "ground" (couplings) or a shaft node
``{ shaft = "name", x = .. }``."""

from typing import Annotated, Literal, Union

from pydantic import Field, model_validator

from .base import Count, Fraction, Integer, Name, NonNegative, Number, Positive, Real, Table, pair, rule
from .fe import Material, ModelSettings, Point, Segment, Support
from .rotor import CampbellTable, RotorTable, SpeedGrid, SpeedGridRpm, SpeedList, SpeedListRpm, _one_of


class ShaftNode(Table):
    """A node of a shaft: ``{ shaft = "name", x = .. }``."""

    shaft: Name
    """The shaft's name."""
    x: Real["m"]
    """Position along that shaft, m (a node)."""
    dof: str | None = None
    """A DOF name at the node (drivers and forces: default the torsion DOF, theta or theta_x)."""


End = Union[Name, ShaftNode]
Ends = Annotated[list[End], Field(min_length=2, max_length=2)]


class TrainTable(Table):
    """``[train]``: the speed reference and the operating speed."""

    reference: Name | None = None
    """The shaft or body whose speed is the train's speed Omega (default: the first shaft, else the first body)."""
    speed: NonNegative["rad/s"] | None = None
    """Operating speed of the reference, rad/s (tooth-pass frequencies of the time simulation, steady states
    and the Floquet analysis at fixed speed)."""
    speed_rpm: NonNegative["rpm"] | None = None
    """Operating speed of the reference, rev/min (or give speed)."""
    start: Literal["rest", "static"] = "rest"
    """Time simulation: start at rest (the bodies' x0, v0) or in the static state under the constant loads (every
    backlash closed on the side the loads press it to)."""

    @model_validator(mode="after")
    def _speed(self):
        _one_of(self, ("speed", "speed_rpm"), False)
        return self


class TrainShaftTable(Table):
    """``[[shaft]]``: a named shaft of the train, an FE shaft (``[shaft.model]`` with ``[[shaft.segment]]``
    etc., as in FE files) or a rotor (``[shaft.rotor]``, as in rotor files), placed at ``position``."""

    name: Name
    """Name of the shaft (ends of connections, outputs)."""
    position: pair("m") = [0.0, 0.0]
    """[y, z] of the shaft axis in the train frame, m (the gears' line of centres follows from it)."""
    x0: Real["m"] = 0.0
    """Axial position of the shaft's x = 0 in the train frame, m (figures)."""
    plane: Literal["y", "z"] = "y"
    """FE bending shafts: the direction of the deflection w."""
    speed_ratio: Real["1"] | None = None
    """Its speed / the reference speed, signed (default: from the meshes and couplings)."""
    model: ModelSettings | None = None
    """[shaft.model]: physics, theory, mass, order (an FE shaft)."""
    material: Material | None = None
    """[shaft.material]: defaults of the FE shaft's segments."""
    segment: Annotated[list[Segment], Field(default_factory=list)]
    """[[shaft.segment]]: the FE shaft's uniform pieces, consecutive from x = 0."""
    support: Annotated[list[Support], Field(default_factory=list)]
    """[[shaft.support]]: supports of the FE shaft."""
    point: Annotated[list[Point], Field(default_factory=list)]
    """[[shaft.point]]: lumped masses, inertias and springs of the FE shaft."""
    rotor: RotorTable | None = None
    """[shaft.rotor]: a rotor shaft (segments, discs, bearings, ... as in rotor files)."""

    @model_validator(mode="after")
    def _one_kind(self):
        if (self.model is None) == (self.rotor is None):
            rule("model", self.model, "either [shaft.model] with [[shaft.segment]] (an FE shaft) or [shaft.rotor] "
                 "(a rotor), exactly one")
        if self.rotor is not None:
            for k in ("material", "segment", "support", "point"):
                if getattr(self, k):
                    rule(k, "given", "not with [shaft.rotor] (a rotor's tables are [shaft.rotor.material], "
                         "[[shaft.rotor.segment]], ...)")
        elif not self.segment:
            rule("segment", None, "at least one [[shaft.segment]] for an FE shaft")
        if self.speed_ratio is not None and self.speed_ratio == 0:
            rule("speed_ratio", 0.0, "a nonzero speed ratio (signed)")
        return self

    @property
    def title(self) -> str:
        return self.name


class TrainBodyTable(Table):
    """``[[body]]``: a rigid body turning about x (motor rotor, wheel, load)."""

    name: Name
    """Name (ends of connections, outputs)."""
    inertia: Positive["kg*m^2"]
    """Moment of inertia about x, kg m^2."""
    x0: Real["rad"] = 0.0
    """Initial angle of its vibration, rad."""
    v0: Real["rad/s"] = 0.0
    """Initial angular velocity of its vibration, rad/s."""
    speed_ratio: Real["1"] | None = None
    """Its speed / the reference speed, signed (default: from the connections)."""


class VariationTable(Table):
    """The periodic part of the mesh stiffness, k(t) = stiffness (1 + sum a_h cos(h w_m t) + b_h sin(h w_m t))
    at the tooth-pass frequency w_m: Fourier coefficients, or a rectangular wave from the contact ratio."""

    fourier: Annotated[list[Annotated[list[Real["1"]], Field(min_length=3, max_length=3)]], Field(min_length=1)] \
        | None = None
    """Rows [h, a_h, b_h] (h: harmonic of the tooth-pass frequency)."""
    contact_ratio: Number(gt=1, lt=2)["1"] | None = None
    """Rectangular wave: contact ratio in (1, 2) (double contact over contact_ratio - 1 of the mesh period)."""
    depth: Number(gt=0, lt=1)["1"] | None = None
    """Rectangular wave: (k_double - k_single) / stiffness."""
    harmonics: Integer(ge=1, le=200) = 25
    """Rectangular wave: Fourier terms kept."""

    @model_validator(mode="after")
    def _one(self):
        rect = self.contact_ratio is not None or self.depth is not None
        if (self.fourier is None) == (not rect):
            rule("fourier", self.fourier, "either fourier = [[h, a_h, b_h], ..] or contact_ratio and depth "
                 "(a rectangular wave)")
        if rect and (self.contact_ratio is None or self.depth is None):
            rule("depth" if self.depth is None else "contact_ratio", None, "both contact_ratio and depth")
        if self.fourier is not None:
            for row in self.fourier:
                if row[0] != int(row[0]) or row[0] < 1:
                    rule("fourier", row, "rows [h, a_h, b_h] with an integer harmonic h >= 1")
        return self


class TransmissionErrorTable(Table):
    """``[[mesh.transmission_error]]``: one harmonic of the static transmission error along the line of
    action, e(t) = amplitude sin(harmonic w_m t + phase)."""

    harmonic: Count = 1
    """Harmonic of the tooth-pass frequency."""
    amplitude: Real["m"]
    """Amplitude along the line of action, m."""
    phase_deg: Real["deg"] = 0.0
    """Phase, degrees."""


class MeshTable(Table):
    """``[[mesh]]``: a gear pair between two ends (shaft nodes or bodies): line of action from the base
    radii (or teeth and module), pressure and helix angles; stiffness and damping along it, backlash on
    both flanks, stiffness variation and static transmission error at the tooth-pass frequency."""

    name: Name | None = None
    """Name (outputs; default mesh<index>)."""
    between: Ends
    """[gear a, gear b]: body names or { shaft = .., x = .. }."""
    stiffness: Positive["N/m"]
    """Mean mesh stiffness along the line of action, N/m."""
    damping: NonNegative["N*s/m"] = 0.0
    """Mesh damping along the line of action, N s/m."""
    base_radius: pair("m") | None = None
    """[r_a, r_b]: base radii (transverse), m."""
    teeth: Annotated[list[Integer(ge=1)], Field(min_length=2, max_length=2)] | None = None
    """[z_a, z_b]: tooth numbers (tooth-pass frequency z_a |Omega_a|; with module: the radii)."""
    module: Positive["m"] | None = None
    """Normal module, m (with teeth, instead of base_radius)."""
    pressure_angle_deg: Number(gt=0, lt=90)["deg"] = 20.0
    """Normal pressure angle, degrees."""
    helix_angle_deg: Number(ge=0, lt=90)["deg"] = 0.0
    """Helix angle, degrees (0: spur)."""
    hand: Literal["right", "left"] = "right"
    """Helix hand of gear a (the sign of the axial component of the line of action)."""
    internal: bool = False
    """An internal pair: gear b is the ring (same sense of rotation)."""
    flank: Literal["positive", "negative"] = "positive"
    """Which of the two lines of action through the pitch point is the drive flank's."""
    line_of_centres_deg: Real["deg"] | None = None
    """Direction of the line of centres from +y towards +z, degrees (default: from the shafts' positions, else 0)."""
    backlash: NonNegative["m"] = 0.0
    """Total backlash along the line of action, m (half on each flank; 0: always in mesh)."""
    damping_in_contact: bool = False
    """The damping acts only while a flank is in contact (default: always, Kahraman & Singh)."""
    variation: VariationTable | None = None
    """[mesh.variation]: periodic mesh stiffness."""
    transmission_error: Annotated[list[TransmissionErrorTable], Field(default_factory=list)]
    """[[mesh.transmission_error]]: static transmission error harmonics."""
    linear_state: Literal["closed", "open"] = "closed"
    """The mesh in linear analyses: closed (mean stiffness) or open (no stiffness)."""

    @model_validator(mode="after")
    def _geometry(self):
        if self.base_radius is None and (self.teeth is None or self.module is None):
            rule("base_radius", None, "base_radius = [r_a, r_b] or teeth = [z_a, z_b] with module = ..")
        if self.base_radius is not None:
            if self.module is not None:
                rule("module", self.module, "either base_radius or teeth with module, not both")
            if min(self.base_radius) <= 0:
                rule("base_radius", self.base_radius, "two base radii > 0 (m)")
        if (self.variation is not None or self.transmission_error) and self.teeth is None:
            rule("teeth", None, "teeth = [z_a, z_b] with a variation or transmission error (the tooth-pass "
                 "frequency is z_a times gear a's speed)")
        return self


class CouplingTable(Table):
    """``[[coupling]]``: springs and dampers between two ends (shaft nodes, bodies or "ground"): torsion and,
    where both ends have them, lateral, angular and axial; optionally a torsional backlash or a slip torque."""

    name: Name | None = None
    """Name (outputs; default coupling<index>)."""
    between: Ends
    """[a, b]: body names, "ground" or { shaft = .., x = .. }."""
    k_torsion: NonNegative["N*m/rad"] = 0.0
    """Torsional stiffness, N m/rad."""
    c_torsion: NonNegative["N*m*s/rad"] = 0.0
    """Torsional damping, N m s/rad."""
    k_lateral: NonNegative["N/m"] = 0.0
    """Lateral stiffness (y and z), N/m."""
    c_lateral: NonNegative["N*s/m"] = 0.0
    """Lateral damping, N s/m."""
    k_angular: NonNegative["N*m/rad"] = 0.0
    """Angular (tilt) stiffness, N m/rad."""
    c_angular: NonNegative["N*m*s/rad"] = 0.0
    """Angular damping, N m s/rad."""
    k_axial: NonNegative["N/m"] = 0.0
    """Axial stiffness, N/m."""
    c_axial: NonNegative["N*s/m"] = 0.0
    """Axial damping, N s/m."""
    backlash: NonNegative["rad"] = 0.0
    """Total torsional backlash, rad (with k_torsion)."""
    slip_torque: Positive["N*m"] | None = None
    """Kinetic slip torque, N m (a slipping coupling, rigid until it slips; no k_torsion)."""
    slip_torque_static: Positive["N*m"] | None = None
    """Breakaway torque, N m (>= slip_torque; default slip_torque)."""
    linear_state: Literal["closed", "open"] | None = None
    """The torsion in linear analyses: closed (the spring) or open (default for a slip coupling)."""


class TrainDriverTable(Table):
    """``[[driver]]``: a prescribed motion x = offset + velocity t + amplitude sin(omega t + phase) of a
    body or a shaft DOF (``at``)."""

    at: End
    """A body name or { shaft = .., x = .., dof = .. } (default DOF: the torsion)."""
    offset: Real["m", "rad"] = 0.0
    """Constant part, rad or m."""
    velocity: Real["m/s", "rad/s"] = 0.0
    """Constant velocity (a drifting rotation), rad/s or m/s."""
    amplitude: Real["m", "rad"] = 0.0
    """Harmonic amplitude."""
    omega: NonNegative["rad/s"] = 0.0
    """Angular frequency, rad/s."""
    phase: Real["rad"] = 0.0
    """Phase, rad."""


class TrainForceTable(Table):
    """``[[force]]``: a load on a body or a shaft DOF (``at``): value + amplitude sin(omega t + phase); with
    ``order`` the frequency is order times the speed of the member it acts on (torque ripple)."""

    at: End
    """A body name or { shaft = .., x = .., dof = .. } (default DOF: the torsion)."""
    value: Real["N", "N*m"] = 0.0
    """Constant part (N or N m)."""
    amplitude: Real["N", "N*m"] = 0.0
    """Harmonic amplitude."""
    omega: NonNegative["rad/s"] | None = None
    """Angular frequency, rad/s."""
    order: Positive["1"] | None = None
    """Instead of omega: harmonic order of the member's speed (omega = order |Omega_i|)."""
    phase: Real["rad"] = 0.0
    """Phase, rad."""

    @model_validator(mode="after")
    def _frequency(self):
        if self.omega is not None and self.order is not None:
            rule("order", self.order, "either omega (rad/s) or order (of the member's speed), not both")
        if self.amplitude != 0 and self.omega is None and self.order is None:
            rule("omega", None, "omega = .. (rad/s) or order = .. with an amplitude")
        return self


class TrainAnalysis(Table):
    """``[analysis]``: the default command (``type``) and the complex modes at a speed."""

    type: Literal["modal", "campbell", "forced", "simulate", "parametric"] = "modal"
    """The command run by default (drivefem demo, the examples' tests)."""
    speed: NonNegative["rad/s"] | None = None
    """Reference speed of drivefem modal, rad/s (default 0)."""
    speed_rpm: NonNegative["rpm"] | None = None
    """Reference speed of drivefem modal, rev/min."""
    modes: Count | None = None
    """Number of modes (default 6)."""
    tolerance: Number(gt=0, lt=1)["1"] = 1e-6
    """Modes with a larger backward error are flagged unreliable."""

    @model_validator(mode="after")
    def _speed(self):
        _one_of(self, ("speed", "speed_rpm"), False)
        return self


class TrainForced(Table):
    """``[forced]``: the linear response over the reference speed to the meshes' transmission error and the
    harmonic [[force]]s (torque ripple of ``order``), about the static state under the constant loads:
    mesh forces and dynamic load factors, bearing reactions."""

    speeds: SpeedList | None = None
    """Reference speeds, rad/s: a list or { start, stop, points }."""
    speeds_rpm: SpeedListRpm | None = None
    """Reference speeds, rev/min."""
    samples: Integer(ge=8, le=4096) = 64
    """Time samples per mesh period of the dynamic load factor."""

    @model_validator(mode="after")
    def _speeds(self):
        _one_of(self, ("speeds", "speeds_rpm"), True)
        return self


class TrainReduction(Table):
    """``[reduction]``: Craig-Bampton reduction of every shaft at its connection, driver and force DOFs."""

    modes: Integer(ge=0) = 6
    """Fixed-interface modes kept per shaft."""
    shaft_modes: dict[str, Integer(ge=0)] = {}
    """Per shaft: { name = modes } overriding modes."""
    static_correction: bool = True
    """Craig-Bampton (constraint modes at the interface DOFs); false: free-interface modes only."""
    threshold: Fraction = 0.95
    """Restitution of the static flexibility below which a warning is issued."""


class DepthAxis(Table):
    """Depths of the mesh-stiffness variation (its size relative to the declared variation)."""

    start: NonNegative["1"] = 0.0
    """Smallest depth."""
    stop: Positive["1"]
    """Largest depth."""
    points: Integer(ge=1) = 21
    """Number of depths."""


class TrainParametric(Table):
    """``[parametric]``: Floquet stability of the linear train with the meshes' periodic stiffness, over the
    reference speed and the depth of the variation (depth 1 = the declared variation)."""

    speeds: SpeedGrid | None = None
    """Reference speeds, rad/s: { start, stop, points }."""
    speeds_rpm: SpeedGridRpm | None = None
    """Reference speeds, rev/min."""
    depth: DepthAxis
    """Depth of the variation: { start, stop, points }."""
    mesh: Name | None = None
    """The [[mesh]] whose variation pulsates (default: the one mesh with a [mesh.variation])."""
    boundaries_at: list[NonNegative["1"]] = []
    """Depths at which the instability intervals are located by root finding."""
    modes: Count | None = None
    """Project on the lowest modes of the mean train (required above 60 free DOFs)."""
    tolerance: Number(gt=0, le=1e-4)["1"] = 1e-10
    """Relative error target of each monodromy matrix."""

    @model_validator(mode="after")
    def _speeds(self):
        _one_of(self, ("speeds", "speeds_rpm"), True)
        return self
