"""Tables of a rotor model file (kind ``rotor``): ``[rotor]`` with its shaft ``[[rotor.segment]]``,
``[[rotor.disc]]``, ``[[rotor.bearing]]``, ``[[rotor.pedestal]]``, ``[[rotor.coupling]]``,
``[[rotor.support]]``, and the analyses ``[analysis]`` (modal at a speed; the default command),
``[campbell]`` (``drivefem campbell``), ``[unbalance_response]`` with ``[[unbalance]]``
(``drivefem forced``), ``[run_up]`` with ``[[rub]]`` and ``[[unbalance]]`` (``drivefem simulate``).  The tables map field for field onto :mod:`fem.rotor.model`, which checks
what involves positions along the shaft (discs, bearings on nodes) and the bearing tables' signs.

Speeds are given in rad/s (``speed``, ``speeds``) or in rev/min (``speed_rpm``, ``speeds_rpm``),
exactly one of the two; a list of speeds may also be a grid ``{ start, stop, points }``.
"""

from typing import Annotated, ClassVar, Literal

from pydantic import Field, model_validator

from .base import Count, Fraction, Integer, NonNegative, Number, Positive, Real, Table, pair, rule

def coefficient(unit: str):
    """A bearing coefficient in ``unit``: a number or a list over the bearing's speeds."""
    return Real[unit] | Annotated[list[Real[unit]], Field(min_length=2)]


BearingStiffness = coefficient("N/m")
BearingDamping = coefficient("N*s/m")


class SpeedGrid(Table):
    """An evenly spaced grid of speeds in rad/s."""

    start: NonNegative["rad/s"]
    """First speed, rad/s."""
    stop: Positive["rad/s"]
    """Last speed (> start), rad/s."""
    points: Integer(ge=2) = 21
    """Number of speeds (>= 2)."""

    @model_validator(mode="after")
    def _order(self):
        if not self.stop > self.start:
            rule("stop", self.stop, f"a speed above start = {self.start}")
        return self


class SpeedGridRpm(SpeedGrid):
    """An evenly spaced grid of speeds in rev/min."""

    start: NonNegative["rpm"]
    """First speed, rev/min."""
    stop: Positive["rpm"]
    """Last speed (> start), rev/min."""


SpeedList = Annotated[list[NonNegative["rad/s"]], Field(min_length=2)] | SpeedGrid
SpeedListRpm = Annotated[list[NonNegative["rpm"]], Field(min_length=2)] | SpeedGridRpm


def _one_of(table, keys: tuple[str, str], required: bool) -> None:
    given = [k for k in keys if getattr(table, k) is not None]
    if len(given) > 1:
        rule(keys[1], getattr(table, keys[1]), f"either {keys[0]} (rad/s) or {keys[1]} (rev/min), not both")
    if required and not given:
        rule(keys[0], None, f"a speed: {keys[0]} = .. (rad/s) or {keys[1]} = .. (rev/min)")


class RotorMaterial(Table):
    """Isotropic shaft material: in ``[rotor.material]`` the defaults of every segment, in a
    segment's ``material`` an override of some of them."""

    E: Positive["Pa"] | None = None
    """Young's modulus, Pa."""
    G: Positive["Pa"] | None = None
    """Shear modulus, Pa (or give nu)."""
    nu: Number(gt=-1, lt=0.5)["1"] | None = None
    """Poisson's ratio in (-1, 0.5): G = E / (2 (1 + nu)) (or give G)."""
    rho: NonNegative["kg/m^3"] | None = None
    """Density, kg/m^3 (0: a massless shaft, the Jeffcott idealisation)."""

    @model_validator(mode="after")
    def _g_or_nu(self):
        if self.G is not None and self.nu is not None:
            rule("nu", self.nu, "either G or nu, not both")
        return self


class RotorLayer(Table):
    """``[[rotor.segment.layer]]``: a further concentric layer of the segment (a sleeve, an impeller
    hub, a shrink fit) on the same nodes: its own annulus and material, its own Timoshenko element
    (own shear parameter Phi; ROSS's convention: shaft elements at one node number are summed).
    ``mass_only = true``: inertia only (translational, rotary and polar), no stiffness."""

    d: Positive["m"]
    """Outer diameter at the segment's start, m."""
    di: NonNegative["m"]
    """Bore at the start, m (e.g. the segment's d for a sleeve on the shaft; layers must not overlap)."""
    d_end: Positive["m"] | None = None
    """Outer diameter at the end, m (default: d)."""
    di_end: NonNegative["m"] | None = None
    """Bore at the end, m (default: di)."""
    material: RotorMaterial | None = None
    """Override of [rotor.material] for this layer (E and G also set its Phi when mass_only)."""
    shear_coefficient: Number(gt=0, le=1.5)["1"] | None = None
    """Timoshenko shear coefficient of the layer (default: Cowper's value for its annulus)."""
    mass_only: bool = False
    """True: the layer adds mass, rotary and polar inertia but no stiffness (a shrunk-on impeller, a sleeve)."""


class RotorSegment(Table):
    """``[[rotor.segment]]``: a piece of shaft, consecutive along x from x = 0, divided into equal
    Timoshenko elements (shear, rotary inertia, gyroscopic matrices); linear taper when d_end or
    di_end is given."""

    length: Positive["m"]
    """Length, m."""
    elements: Count
    """Number of equal Timoshenko elements."""
    d: Positive["m"]
    """Outer diameter at the start, m."""
    d_end: Positive["m"] | None = None
    """Outer diameter at the end, m (default: d; otherwise a linear taper)."""
    di: NonNegative["m"] = 0.0
    """Bore at the start, m (0: solid)."""
    di_end: NonNegative["m"] | None = None
    """Bore at the end, m (default: di)."""
    material: RotorMaterial | None = None
    """Override of [rotor.material] for this segment."""
    shear_coefficient: Number(gt=0, le=1.5)["1"] | None = None
    """Timoshenko shear coefficient kappa (default: Cowper's value for the hollow circle)."""
    added_mass_per_length: NonNegative["kg/m"] = 0.0
    """Non-structural mass carried by the segment, kg/m (translational inertia only, no stiffness)."""
    layer: Annotated[list[RotorLayer], Field(default_factory=list)]
    """[[rotor.segment.layer]]: further concentric layers (own material; mass_only for inertia without stiffness)."""


class RotorDisc(Table):
    """``[[rotor.disc]]``: a rigid disc at a shaft node, given by its inertia (mass, Id, Ip) or by
    its geometry (width, d, di, rho: a uniform annulus), not both."""

    x: Real["m"]
    """Position along the shaft, m (a node: segment end or element boundary)."""
    mass: NonNegative["kg"] | None = None
    """Mass, kg."""
    Id: NonNegative["kg*m^2"] | None = None
    """Diametral moment of inertia about the disc's centre, kg m^2."""
    Ip: NonNegative["kg*m^2"] | None = None
    """Polar moment of inertia, kg m^2 (gyroscopic moments Ip Omega)."""
    width: Positive["m"] | None = None
    """Geometry: axial width, m."""
    d: Positive["m"] | None = None
    """Geometry: outer diameter, m."""
    di: NonNegative["m"] | None = None
    """Geometry: bore, m (default 0)."""
    rho: Positive["kg/m^3"] | None = None
    """Geometry: density, kg/m^3 (default: that of [rotor.material])."""
    name: str = ""
    """Label in outputs."""

    @model_validator(mode="after")
    def _inertia_or_geometry(self):
        inertia = [k for k in ("mass", "Id", "Ip") if getattr(self, k) is not None]
        geometry = [k for k in ("width", "d", "di", "rho") if getattr(self, k) is not None]
        if inertia and geometry:
            rule(geometry[0], getattr(self, geometry[0]), "either the inertia (mass, Id, Ip) or the geometry "
                 "(width, d, di, rho) of a disc, not both")
        if geometry and (self.width is None or self.d is None):
            rule("width" if self.width is None else "d", None, "both width and d for a disc given by its geometry")
        if not inertia and not geometry:
            rule("mass", None, "the inertia (mass, Id, Ip) or the geometry (width, d, di, rho) of the disc")
        return self


class RotorBearing(Table):
    """``[[rotor.bearing]]``: a linear bearing or seal on (v, w) of a shaft node: force on the shaft
    f = -K d - C d', K = [[kyy, kyz], [kzy, kzz]], C = [[cyy, cyz], [czy, czz]].  Each coefficient is
    a number or a list over ``speeds``/``speeds_rpm`` (interpolated; outside the table as
    ``extrapolate`` says).  Stiffness may have any sign (seals); the damping's symmetric part must be
    positive semidefinite (cyy, czz >= 0, cyy czz >= ((cyz + czy)/2)^2); some direct coefficient != 0."""

    x: Real["m"]
    """Position along the shaft, m (a node)."""
    kyy: BearingStiffness = 0.0
    """Direct stiffness in y, N/m (any sign: a seal's may be negative)."""
    kyz: BearingStiffness = 0.0
    """Cross-coupled stiffness, N/m (force in y per displacement in z)."""
    kzy: BearingStiffness = 0.0
    """Cross-coupled stiffness, N/m (force in z per displacement in y)."""
    kzz: BearingStiffness = 0.0
    """Direct stiffness in z, N/m (any sign)."""
    cyy: BearingDamping = 0.0
    """Direct damping in y, N s/m (>= 0)."""
    cyz: BearingDamping = 0.0
    """Cross-coupled damping, N s/m."""
    czy: BearingDamping = 0.0
    """Cross-coupled damping, N s/m."""
    czz: BearingDamping = 0.0
    """Direct damping in z, N s/m (>= 0)."""
    speeds: Annotated[list[NonNegative["rad/s"]], Field(min_length=2)] | None = None
    """Speeds of a coefficient table, rad/s, increasing."""
    speeds_rpm: Annotated[list[NonNegative["rpm"]], Field(min_length=2)] | None = None
    """Speeds of a coefficient table, rev/min, increasing (or give speeds)."""
    interpolation: Literal["linear", "pchip", "spline", "smoothing-spline"] = "linear"
    """Interpolation of a table between its speeds (pchip: shape-preserving cubic; spline: cubic spline
    through the points, not-a-knot ends; smoothing-spline: ROSS's convention, a cubic smoothing spline
    with s = number of points (scipy's UnivariateSpline) -- not an interpolant, it misses the table's
    points)."""
    extrapolate: Literal["refuse", "hold", "linear", "continue"] = "refuse"
    """A speed outside the table: refuse (an error), hold (the end values), linear (the interpolant's
    tangent line at the table's end) or continue (the interpolant's end pieces continued; with
    smoothing-spline ROSS's extrapolation); hold, linear and continue warn, naming the bearing and the
    speeds."""
    k_axial: NonNegative["N/m"] = 0.0
    """Thrust-bearing stiffness on u, N/m (dofs = "full" only)."""
    c_axial: NonNegative["N*s/m"] = 0.0
    """Thrust-bearing damping on u, N s/m (dofs = "full" only)."""
    pedestal: str | None = None
    """Name of the [[rotor.pedestal]] the bearing sits on (default: ground)."""
    name: str = ""
    """Label in outputs."""

    @model_validator(mode="after")
    def _speeds(self):
        _one_of(self, ("speeds", "speeds_rpm"), required=False)
        tabulated = [k for k in ("kyy", "kyz", "kzy", "kzz", "cyy", "cyz", "czy", "czz")
                     if isinstance(getattr(self, k), list)]
        if tabulated and self.speeds is None and self.speeds_rpm is None:
            rule(tabulated[0], getattr(self, tabulated[0]), "a number, or give speeds (rad/s) or speeds_rpm "
                 "for a speed-dependent table")
        return self


class RotorJournalBearing(Table):
    """``[[rotor.journal_bearing]]``: a plain (cylindrical) journal bearing computed from its geometry:
    the isoviscous Reynolds equation of the film over the bearing surface (scikit-fem; cavitation by
    Reynolds' (Swift-Stieber) condition, or Guembel's), the operating point under the static load at
    every table speed and the 8 coefficients there (modal, campbell, forced use the table; a run-up,
    drivefem simulate, applies the nonlinear film force instead)."""

    x: Real["m"]
    """Position along the shaft, m (a node)."""
    diameter: Positive["m"]
    """Journal diameter D, m."""
    length: Positive["m"]
    """Bearing length L, m."""
    clearance: Positive["m"]
    """Radial clearance c, m (typically 1e-3 D)."""
    viscosity: Positive["Pa*s"]
    """Lubricant dynamic viscosity mu, Pa s (isoviscous film)."""
    load: Positive["N"] | None = None
    """Static load the bearing carries, N (default: the rotor's weight share on rigid supports at its bearings)."""
    load_angle_deg: Real["deg"] = -90.0
    """Direction of the static load the shaft puts on the bearing, degrees from +y towards +z (-90: gravity along -z)."""
    film: Literal["reynolds", "short"] = "reynolds"
    """reynolds: finite-length film solved by finite elements; short: Ocvirk's short-bearing closed form (pi film)."""
    cavitation: Literal["reynolds", "gumbel"] = "reynolds"
    """Film rupture of the finite film: reynolds (Swift-Stieber: p >= 0 with zero gradient at rupture) or gumbel (half-Sommerfeld)."""
    grooves_deg: Annotated[list[pair("deg")], Field(max_length=8)] = []
    """Axial supply grooves at ambient pressure, [[centre, width], ...] in degrees (centre from +y towards +z; finite film only)."""
    mesh: Annotated[list[Integer(ge=2, le=2000)], Field(min_length=2, max_length=2)] = [144, 16]
    """Finite film mesh: [elements around (>= 12), elements along the half length]."""
    speeds: Annotated[list[Positive["rad/s"]], Field(min_length=2)] | None = None
    """Speeds of the coefficient table, rad/s (> 0, increasing)."""
    speeds_rpm: Annotated[list[Positive["rpm"]], Field(min_length=2)] | SpeedGridRpm | None = None
    """Speeds of the coefficient table, rev/min (or give speeds): a list or a grid { start, stop, points }."""
    interpolation: Literal["linear", "pchip"] = "pchip"
    """Interpolation of the table between its speeds."""
    pedestal: str | None = None
    """Name of the [[rotor.pedestal]] the bearing sits on (default: ground)."""
    name: str = ""
    """Label in outputs."""

    @model_validator(mode="after")
    def _speeds(self):
        _one_of(self, ("speeds", "speeds_rpm"), required=True)
        if isinstance(self.speeds_rpm, SpeedGrid) and self.speeds_rpm.start <= 0:
            rule("speeds_rpm", self.speeds_rpm.start, "a grid starting above 0 (the film carries no load at rest)")
        return self


class RotorRollingBearing(Table):
    """``[[rotor.rolling_bearing]]``: a radial ball or roller bearing with radial clearance: Hertzian
    elements (load-deflection exponent 3/2 balls, 10/9 rollers) on a cage turning at the epicyclic
    speed; the linear analyses use the stiffness at the static load (averaged over the cage
    positions), a run-up the nonlinear clearance law element by element."""

    unit_choice: ClassVar[dict] = {"contact_stiffness": ("element", {"ball": (0,), "roller": (1,)})}

    x: Real["m"]
    """Position along the shaft, m (a node)."""
    element: Literal["ball", "roller"] = "ball"
    """Rolling elements: ball (point contact) or roller (line contact)."""
    elements: Integer(ge=3)
    """Number of rolling elements Z."""
    element_diameter: Positive["m"] | None = None
    """Ball or roller diameter D, m."""
    pitch_diameter: Positive["m"] | None = None
    """Pitch diameter d_m, m."""
    contact_angle_deg: Number(ge=0, lt=90)["deg"] = 0.0
    """Contact angle alpha, degrees."""
    clearance: Real["m"] = 0.0
    """Radial clearance (play per side: half the diametral clearance), m; negative: a preload."""
    inner_conformity: Number(gt=0.5, lt=1)["1"] = 0.52
    """Ball bearings: inner groove radius / ball diameter."""
    outer_conformity: Number(gt=0.5, lt=1)["1"] = 0.52
    """Ball bearings: outer groove radius / ball diameter."""
    roller_length: Positive["m"] | None = None
    """Roller bearings: effective roller length, m."""
    modulus: Positive["Pa"] = 208e9
    """Young's modulus of rings and elements, Pa."""
    poisson: Number(gt=-1, lt=0.5)["1"] = 0.3
    """Poisson's ratio of rings and elements."""
    contact_stiffness: Positive["N/m^1.5", "N/m^(10/9)"] | None = None
    """Load-deflection constant K_n of one element between both races, N/m^n (instead of the geometry)."""
    damping: NonNegative["N*s/m"] = 0.0
    """Viscous damping of the bearing in y and z, N s/m."""
    load: NonNegative["N"] | None = None
    """Static load the bearing carries, N (default: the rotor's weight share)."""
    load_angle_deg: Real["deg"] = -90.0
    """Direction of the static load the shaft puts on the bearing, degrees from +y towards +z."""
    pedestal: str | None = None
    """Name of the [[rotor.pedestal]] the bearing sits on (default: ground)."""
    name: str = ""
    """Label in outputs."""


class RotorSqueezeFilmDamper(Table):
    """``[[rotor.squeeze_film_damper]]``: a squeeze-film damper (non-rotating journal in an oil film,
    centred by a spring): short-bearing film in closed form, pi film (cavitated) or 2pi film; the
    linear analyses use the centring stiffness and the film's damping at the static position, a
    run-up the nonlinear film force."""

    x: Real["m"]
    """Position along the shaft, m (a node)."""
    diameter: Positive["m"]
    """Damper journal diameter D, m."""
    length: Positive["m"]
    """Damper land length L, m."""
    clearance: Positive["m"]
    """Radial clearance c, m."""
    viscosity: Positive["Pa*s"]
    """Lubricant dynamic viscosity mu, Pa s."""
    film: Literal["pi", "2pi"] = "pi"
    """pi: cavitated film (half the circumference pressurised); 2pi: full film."""
    centering_stiffness: NonNegative["N/m"] = 0.0
    """Stiffness of the centring spring (squirrel cage) in y and z, N/m."""
    load: NonNegative["N"] = 0.0
    """Static load on the damper, N (carried by the centring spring)."""
    load_angle_deg: Real["deg"] = -90.0
    """Direction of the static load, degrees from +y towards +z."""
    pedestal: str | None = None
    """Name of the [[rotor.pedestal]] the damper sits on (default: ground)."""
    name: str = ""
    """Label in outputs."""


class RotorPedestal(Table):
    """``[[rotor.pedestal]]``: a support with its own mass between bearings and ground."""

    name: Annotated[str, Field(min_length=1)]
    """Name the bearings refer to."""
    mass: Positive["kg"]
    """Mass, kg (moves in y and z)."""
    kyy: Positive["N/m"]
    """Stiffness to ground in y, N/m."""
    kzz: Positive["N/m"]
    """Stiffness to ground in z, N/m."""
    cyy: NonNegative["N*s/m"] = 0.0
    """Damping to ground in y, N s/m."""
    czz: NonNegative["N*s/m"] = 0.0
    """Damping to ground in z, N s/m."""


class RotorCoupling(Table):
    """``[[rotor.coupling]]``: a flexible coupling at a junction of two segments (the shaft is cut
    there and joined by springs and dampers)."""

    x: Real["m"]
    """Position, m: a junction of two [[rotor.segment]]s."""
    k_lateral: Positive["N/m"]
    """Lateral stiffness (v, w), N/m."""
    k_angular: Positive["N*m/rad"]
    """Angular stiffness (theta_y, theta_z), N m/rad."""
    k_axial: NonNegative["N/m"] = 0.0
    """Axial stiffness, N/m (dofs = "full": > 0)."""
    k_torsion: NonNegative["N*m/rad"] = 0.0
    """Torsional stiffness, N m/rad (dofs = "full": > 0)."""
    c_lateral: NonNegative["N*s/m"] = 0.0
    """Lateral damping, N s/m."""
    c_angular: NonNegative["N*m*s/rad"] = 0.0
    """Angular damping, N m s/rad."""
    mass: NonNegative["kg"] = 0.0
    """Own mass, kg (split equally between the two ends)."""
    Id: NonNegative["kg*m^2"] = 0.0
    """Own diametral inertia, kg m^2."""
    Ip: NonNegative["kg*m^2"] = 0.0
    """Own polar inertia, kg m^2."""
    name: str = ""
    """Label in outputs."""


class RotorSupport(Table):
    """``[[rotor.support]]``: a rigid constraint: the listed DOFs of the node at x are held at zero."""

    x: Real["m"]
    """Position, m (a node)."""
    dofs: Annotated[list[Literal["u", "v", "w", "theta_x", "theta_y", "theta_z"]], Field(min_length=1)] = ["v", "w"]
    """Held DOFs (u and theta_x only with dofs = "full")."""


class RotorTable(Table):
    """``[rotor]``: the shaft line, its discs, bearings and seals, pedestals, couplings and supports.
    Axes: x along the shaft (spin axis), y and z lateral; per node v, w, theta_y, theta_z (and u,
    theta_x with dofs = "full")."""

    dofs: Literal["lateral", "full"] = "lateral"
    """DOFs per node: lateral (v, w, theta_y, theta_z) or full (also axial u and torsion theta_x)."""
    material: RotorMaterial | None = None
    """[rotor.material]: defaults of every segment (E, G or nu, rho)."""
    segment: Annotated[list[RotorSegment], Field(min_length=1)]
    """[[rotor.segment]]: shaft pieces, consecutive from x = 0."""
    disc: Annotated[list[RotorDisc], Field(default_factory=list)]
    """[[rotor.disc]]: rigid discs."""
    bearing: Annotated[list[RotorBearing], Field(default_factory=list)]
    """[[rotor.bearing]]: linear bearings and seals (8 coefficients, constant or speed tables)."""
    journal_bearing: Annotated[list[RotorJournalBearing], Field(default_factory=list)]
    """[[rotor.journal_bearing]]: plain journal bearings computed from their geometry (Reynolds equation)."""
    rolling_bearing: Annotated[list[RotorRollingBearing], Field(default_factory=list)]
    """[[rotor.rolling_bearing]]: ball or roller bearings with radial clearance (Hertzian elements)."""
    squeeze_film_damper: Annotated[list[RotorSqueezeFilmDamper], Field(default_factory=list)]
    """[[rotor.squeeze_film_damper]]: squeeze-film dampers (short-bearing closed form)."""
    pedestal: Annotated[list[RotorPedestal], Field(default_factory=list)]
    """[[rotor.pedestal]]: bearing supports with their own mass."""
    coupling: Annotated[list[RotorCoupling], Field(default_factory=list)]
    """[[rotor.coupling]]: flexible couplings at segment junctions."""
    support: Annotated[list[RotorSupport], Field(default_factory=list)]
    """[[rotor.support]]: rigid constraints."""


class RotorAnalysis(Table):
    """``[analysis]`` of a rotor file: ``type`` names the default command (what the examples and
    ``drivefem demo`` run); the other keys are the complex modal analysis at one speed
    (``drivefem modal``)."""

    type: Literal["modal", "forced", "campbell", "simulate"] = "modal"
    """Default command: modal (complex modes at a speed), forced (unbalance response), campbell,
    simulate (the run-up of [run_up] with its rubs)."""
    speed: NonNegative["rad/s"] | None = None
    """Modal: spin speed, rad/s (or speed_rpm; default 0)."""
    speed_rpm: NonNegative["rpm"] | None = None
    """Modal: spin speed, rev/min."""
    modes: Count | None = None
    """Modes (one per conjugate pair, lowest |lambda| first; default 6, capped at the DOFs)."""
    tolerance: Number(gt=0, lt=1)["1"] = 1e-6
    """Relative eigen-residual above which a mode is reported as not reliable."""

    @model_validator(mode="after")
    def _speed(self):
        _one_of(self, ("speed", "speed_rpm"), required=False)
        return self


class CampbellTable(Table):
    """``[campbell]``: the Campbell diagram of ``drivefem campbell`` (modes tracked by shape
    correlation) and the critical speeds as roots of omega(Omega) = k Omega."""

    speeds: SpeedList | None = None
    """Speeds, rad/s: a list (increasing, >= 0) or a grid { start, stop, points }."""
    speeds_rpm: SpeedListRpm | None = None
    """Speeds, rev/min (or give speeds)."""
    modes: Count | None = None
    """Tracked modes (default: [analysis] modes, else 6)."""
    orders: Annotated[list[Positive["1"]], Field(min_length=1)] = [1.0]
    """Excitation orders k of the lines omega = k Omega (1: synchronous)."""
    critical: bool = True
    """Find the critical speeds (roots of omega_j(Omega) = k Omega by Brent's method)."""
    operating_range: Annotated[list[Positive["rad/s"]], Field(min_length=2, max_length=2)] | None = None
    """Operating speed range [min, max], rad/s, shaded on the diagram (default: [unbalance_response]'s)."""
    operating_range_rpm: Annotated[list[Positive["rpm"]], Field(min_length=2, max_length=2)] | None = None
    """Operating speed range [min, max], rev/min."""

    @model_validator(mode="after")
    def _speeds(self):
        _one_of(self, ("speeds", "speeds_rpm"), required=True)
        _one_of(self, ("operating_range", "operating_range_rpm"), required=False)
        return self


class RotorProbe(Table):
    """``[[unbalance_response.probe]]``: a response output at a node."""

    x: Real["m"]
    """Position, m (a node)."""
    direction: Literal["v", "w", "major"] = "major"
    """v, w, or the orbit's semi-major axis."""
    name: Annotated[str, Field(min_length=1)] | None = None
    """Name of the output (default: the name of the disc, bearing or coupling at x, else direction@x=..)."""


class UnbalanceResponseTable(Table):
    """``[unbalance_response]``: the synchronous unbalance response of ``drivefem forced`` (amplitude
    and phase along the shaft, peaks with API 684-style amplification factors and separation
    margins)."""

    speeds: SpeedList | None = None
    """Speeds, rad/s (> 0): a list or a grid { start, stop, points }."""
    speeds_rpm: SpeedListRpm | None = None
    """Speeds, rev/min (or give speeds)."""
    operating_range: Annotated[list[Positive["rad/s"]], Field(min_length=2, max_length=2)] | None = None
    """Operating speed range [min, max], rad/s (for the separation margins)."""
    operating_range_rpm: Annotated[list[Positive["rpm"]], Field(min_length=2, max_length=2)] | None = None
    """Operating speed range [min, max], rev/min."""
    probe: Annotated[list[RotorProbe], Field(default_factory=list)]
    """[[unbalance_response.probe]]: outputs (default: the orbit at every disc and bearing)."""
    peaks: bool = True
    """Refine the peaks and their half-power speeds (AF, separation margins)."""

    @model_validator(mode="after")
    def _speeds(self):
        _one_of(self, ("speeds", "speeds_rpm"), required=True)
        _one_of(self, ("operating_range", "operating_range_rpm"), required=False)
        return self


class UnbalanceTable(Table):
    """``[[unbalance]]``: a mass unbalance m_u e at a node, at an angle from +y towards +z in the
    rotating frame."""

    x: Real["m"]
    """Position, m (a node)."""
    magnitude: Positive["kg*m"]
    """m_u e, kg m."""
    phase_deg: Real["deg"] = 0.0
    """Angle from +y towards +z, degrees."""


class RubTable(Table):
    """``[[rub]]``: a stator ring of radial clearance around the shaft at a node (seal or casing rub, or
    a bearing clearance: the bearing's stiffness as ``stiffness``, friction 0), for ``drivefem
    simulate``.  Compliant contact (``stiffness``, ``damping``: [run_up] method = "event") or rigid
    contact with Newton's restitution (no ``stiffness``: method = "moreau"); Coulomb friction at the
    contact point.  Linear analyses (modal, campbell, forced) do not see it."""

    x: Real["m"]
    """Position, m (a node)."""
    clearance: Positive["m"]
    """Radial clearance, m."""
    stiffness: Positive["N/m"] | None = None
    """Contact stiffness, N/m (leave out: a rigid contact)."""
    damping: NonNegative["N*s/m"] = 0.0
    """Contact damping, N s/m (compliant contact)."""
    restitution: Fraction = 0.5
    """Newton's restitution coefficient (rigid contact)."""
    friction: NonNegative["1"] = 0.0
    """Coulomb friction coefficient at the contact point."""
    radius: Positive["m"] | None = None
    """Shaft radius at the contact, m (the surface speed Omega R; default: half the outer diameter there)."""
    centre: Annotated[list[Real["m"]], Field(min_length=2, max_length=2)] = [0.0, 0.0]
    """Offset [c_y, c_z] of the stator centre from the undeformed shaft axis, m."""
    name: str = ""
    """Label in outputs."""


class RunUpTable(Table):
    """``[run_up]``: a run-up (coast-down, constant speed) of ``drivefem simulate``: the speed goes
    linearly from speed_start to speed_end over duration; the reduced rotor (modes at rest plus
    attachment shapes at the rubs) is integrated with the [[rub]]s and [[unbalance]]s."""

    speed_start: NonNegative["rad/s"] | None = None
    """First speed, rad/s (or speed_start_rpm)."""
    speed_start_rpm: NonNegative["rpm"] | None = None
    """First speed, rev/min."""
    speed_end: NonNegative["rad/s"] | None = None
    """Last speed, rad/s (or speed_end_rpm; equal to speed_start: constant speed)."""
    speed_end_rpm: NonNegative["rpm"] | None = None
    """Last speed, rev/min."""
    duration: Positive["s"]
    """Duration of the ramp, s."""
    method: Literal["event", "moreau"] = "event"
    """event: compliant rubs, contact changes located exactly; moreau: rigid rubs (Moreau-Jean)."""
    modes: Count = 12
    """Retained modes at rest (plus two static attachment shapes per rub)."""
    time_step: Positive["s"] | None = None
    """Moreau-Jean step, s (default: a 40th of the shortest retained period)."""
    output_step: Positive["s"] | None = None
    """Sampling of the outputs, s (default: a 64th of the shortest revolution; at most 20 000 samples)."""
    rtol: Number(ge=1e-13, le=1e-3)["1"] = 1e-8
    """Relative tolerance of the event-located integrator."""
    start: Literal["steady", "rest"] = "steady"
    """steady: the linear synchronous orbit at speed_start (about the static state of bearings computed from their geometry); rest: zero displacement and velocity."""
    max_events: Count = 100_000
    """A chattering contact stops the run beyond this many contact events."""
    integrator: Literal["auto", "DOP853", "LSODA"] = "auto"
    """Integrator of method = "event": DOP853 (explicit), LSODA (BDF where stiff: fluid films on light journals), auto (LSODA with bearings computed from their geometry, else DOP853)."""

    @model_validator(mode="after")
    def _speeds(self):
        _one_of(self, ("speed_start", "speed_start_rpm"), required=True)
        _one_of(self, ("speed_end", "speed_end_rpm"), required=True)
        return self


class StaticLoadTable(Table):
    """``[[static.load]]``: a static point force at a node (N)."""

    x: Real["m"]
    """Position, m (a node)."""
    fy: Real["N"] = 0.0
    """Force along y, N."""
    fz: Real["N"] = 0.0
    """Force along z, N."""
    fx: Real["N"] = 0.0
    """Axial force, N (dofs = "full")."""


class StaticTable(Table):
    """``[static]``: the static deflection of ``drivefem static`` (sag under gravity and point loads,
    bearing loads); all keys optional (default: gravity 9.81 m/s^2 along -z, bearings at rest)."""

    gravity: Annotated[list[Real["m/s^2"]], Field(min_length=3, max_length=3)] = [0.0, 0.0, -9.81]
    """Acceleration of gravity (g_x, g_y, g_z), m/s^2."""
    speed: NonNegative["rad/s"] | None = None
    """Speed at which tabulated bearings are taken, rad/s (or speed_rpm; default: the [analysis] speed, else 0)."""
    speed_rpm: NonNegative["rpm"] | None = None
    """The same, rev/min."""
    load: Annotated[list[StaticLoadTable], Field(default_factory=list)]
    """[[static.load]]: point forces."""

    @model_validator(mode="after")
    def _speed(self):
        _one_of(self, ("speed", "speed_rpm"), required=False)
        return self


class CriticalMapTable(Table):
    """``[critical_map]``: the undamped critical speed map of ``drivefem critical-map`` (synchronous
    critical speeds with every bearing replaced by an isotropic one of each stiffness), with the
    model's own bearing stiffness overlaid; all keys optional."""

    stiffness: Annotated[list[Positive["N/m"]], Field(min_length=2, max_length=2)] | None = None
    """[lowest, highest] bearing stiffness, N/m (default: two decades either side of the model's bearings)."""
    points: Integer(ge=3, le=400) = 41
    """Stiffness values, logarithmically spaced."""
    modes: Count = 4
    """Forward critical speeds drawn (the lowest)."""
    bearings: list[str] | None = None
    """Names of the [[rotor.bearing]]s the map varies (default: every one with a positive direct stiffness);
    the others (seals, dampers) are left out of the map."""


class Level1StageTable(Table):
    """``[[stability.api_level1.stage]]``: an impeller or axial stage (Wachel's anticipated cross-coupling)."""

    x: Real["m"]
    """Position, m."""
    power: Positive["W"]
    """Rated power of the stage, W."""
    diameter: Positive["m"]
    """Impeller diameter D_c, m (axial: blade pitch diameter D_t)."""
    width: Positive["m"]
    """Smaller of impeller discharge width and diffuser width H_c, m (axial: effective blade height H_t)."""
    density_ratio: Positive["1"] = 1.0
    """Discharge / suction gas density of the stage (centrifugal)."""
    name: str = ""
    """A name for reports."""


class Level1Table(Table):
    """``[stability.api_level1]``: the API 617 (7th ed.) / API RP 684 (2nd ed.) Level I screening:
    log decrement of the first forward mode against cross-coupling 0 ... 10 Q_A at the maximum
    continuous speed; Level II is required when Q0/QA < 2 or the log decrement at QA < 0.1."""

    speed: Positive["rad/s"] | None = None
    """Maximum continuous speed, rad/s (or speed_rpm; default: the top of the operating range)."""
    speed_rpm: Positive["rpm"] | None = None
    """Maximum continuous speed, rev/min."""
    machine: Literal["centrifugal", "axial"] = "centrifugal"
    """centrifugal (B_c = 3, density ratio) or axial (turbines, axial compressors: B_t = 1.5)."""
    placement: Literal["auto", "mid-span", "stages"] = "auto"
    """Where Q acts: mid-span (between-bearing rotors), the stages (overhung), auto (mid-span when every stage is
    between the bearings)."""
    exclude: list[str] = []
    """Names of [[rotor.bearing]]s left out (seals: Q_A stands for them at Level I)."""
    points: Integer(ge=3, le=201) = 21
    """Cross-coupling values from 0 to 10 Q_A."""
    stage: Annotated[list[Level1StageTable], Field(min_length=1)]
    """[[stability.api_level1.stage]]: the stages."""

    @model_validator(mode="after")
    def _speed(self):
        _one_of(self, ("speed", "speed_rpm"), required=False)
        return self


class StabilityTable(Table):
    """``[stability]``: ``drivefem stability``: the stability threshold (lowest speed where a tracked
    mode's log decrement crosses zero) over a speed range, and optionally the API Level I screening."""

    speeds: SpeedList | None = None
    """Speeds scanned, rad/s (> 0; the grid brackets, Brent's method converges): a list or a grid."""
    speeds_rpm: SpeedListRpm | None = None
    """The same, rev/min (default: the [campbell] speeds)."""
    modes: Count | None = None
    """Tracked modes (default: [campbell] modes, [analysis] modes, else 6)."""
    api_level1: Level1Table | None = None
    """[stability.api_level1]: the API Level I screening."""

    @model_validator(mode="after")
    def _speeds(self):
        _one_of(self, ("speeds", "speeds_rpm"), required=False)
        return self
