"""Tables of the linear analyses: ``[analysis]`` (modal, forced or parametric), ``[damping]``, ``[[load]]``,
``[[base_motion]]`` and ``[[response]]``.  ``[damping]`` has one meaning in every kind of file:
the global damping added to the model's own dampers and dissipation coefficients (design.md §3)."""

from typing import Annotated, ClassVar, Literal, Union

from pydantic import Discriminator, Field, Tag, model_validator

from .base import Count, Integer, NonNegative, Number, Positive, Real, Table, rule


class SweepHz(Table):
    """A frequency grid in Hz."""

    start: NonNegative["Hz"]
    """First frequency, Hz."""
    stop: Positive["Hz"]
    """Last frequency, Hz (> start)."""
    points: Count = 200
    """Number of frequencies."""
    spacing: Literal["linear", "log"] = "linear"
    """Linear or logarithmic spacing."""

    @model_validator(mode="after")
    def _order(self):
        if not self.stop > self.start:
            rule("stop", self.stop, f"a frequency above start = {self.start}")
        if self.spacing == "log" and self.start <= 0:
            rule("start", self.start, "a frequency > 0 for spacing = 'log'")
        return self


class ModalAnalysis(Table):
    """``[analysis] type = "modal"``: natural frequencies and mode shapes."""

    type: Literal["modal"] = "modal"
    modes: Count | None = None
    """Number of modes (default 6, capped at the number of free DOFs)."""
    shift: Real["rad^2/s^2"] | None = None
    """Shift of the shift-invert eigensolver, rad^2/s^2 (default: automatic)."""
    tolerance: Number(gt=0, lt=1)["1"] = 1e-5
    """Relative residual above which a mode is reported as not reliable."""
    convergence_n: Annotated[list[Count], Field(min_length=1)] | None = None
    """Drive files: mechanism counts n of the convergence study towards the pseudo-medium."""


class ForcedAnalysis(Table):
    """``[analysis] type = "forced"``: harmonic response over a frequency list (linear models), or
    the amplitude-frequency curve of the ``[steady]`` table (nonlinear models)."""

    type: Literal["forced"]
    frequencies_hz: Annotated[list[NonNegative["Hz"]], Field(min_length=1)] | None = None
    """Forcing frequencies, Hz."""
    omega_rad_s: Annotated[list[NonNegative["rad/s"]], Field(min_length=1)] | None = None
    """Forcing angular frequencies, rad/s."""
    sweep_hz: SweepHz | None = None
    """A grid: { start, stop, points, spacing = "linear" | "log" }, Hz."""
    method: Literal["direct", "modal"] = "direct"
    """Direct sparse solve per frequency, or modal superposition."""
    modes: Count | None = None
    """Modes of the modal superposition (default min(20, free DOFs))."""
    convergence_n: Annotated[list[Count], Field(min_length=1)] | None = None
    """Drive files: mechanism counts n of the convergence study."""
    period: Positive["s"] | None = None
    """Periodic non-harmonic loads ([[load]] waveform): the period T, s -- the response is the Fourier
    superposition of the harmonics j 2 pi/T, j = 0..harmonics (textbook §5.8), instead of a frequency list."""
    harmonics: Integer(ge=1, le=2000) = 64
    """With period: the number of harmonics of the superposition."""

    @property
    def frequency_keys(self) -> list[str]:
        return [k for k in ("frequencies_hz", "omega_rad_s", "sweep_hz") if getattr(self, k) is not None]


class OmegaGrid(Table):
    """An excitation-frequency grid of the parametric chart: ``{ start, stop, points }``, rad/s."""

    start: Positive["rad/s"]
    """First excitation frequency Omega, rad/s."""
    stop: Positive["rad/s"]
    """Last excitation frequency (> start), rad/s."""
    points: Integer(ge=2) = 161
    """Number of equally spaced frequencies."""

    @model_validator(mode="after")
    def _order(self):
        if not self.stop > self.start:
            rule("stop", self.stop, f"a frequency above start = {self.start}")
        return self


class OmegaRatioGrid(OmegaGrid):
    """An excitation-frequency grid of the parametric chart as ratios Omega / omega_1: ``{ start, stop, points }``."""

    start: Positive["1"]
    """First ratio Omega / omega_1."""
    stop: Positive["1"]
    """Last ratio Omega / omega_1 (> start)."""


class DepthGrid(Table):
    """The depth grid of the parametric chart (its vertical axis eps): ``{ max, min, points }``."""

    max: Positive["1"]
    """Largest depth of pulsation eps (below the depth at which K(t) or M(t) stops being positive definite)."""
    min: NonNegative["1"] = 0.0
    """Smallest depth eps (< max)."""
    points: Count = 41
    """Number of equally spaced depths."""

    @model_validator(mode="after")
    def _order(self):
        if not self.max > self.min:
            rule("max", self.max, f"a depth above min = {self.min}")
        return self


class Modulation(Table):
    """``[[analysis.modulation]]``: one pulsating term, ``-eps * depth * P * sin(harmonic * Omega t + phase)``
    added to K (``target = "stiffness"``) or to M (``"inertia"``), textbook (7.1)-(7.7).  ``P`` is the part of
    the matrix named by one of ``spring``, ``body``, ``segment``, ``point``; none of them: the whole K or M."""

    target: Literal["stiffness", "inertia"] = "stiffness"
    """What pulsates: the stiffness K or the inertia M (variable reduced inertia of a mechanism)."""
    spring: Count | None = None
    """Lumped models: the [[spring]] (1-based, in file order) whose stiffness pulsates."""
    body: Annotated[str, Field(min_length=1)] | None = None
    """Lumped models: the [[body]] (name) whose inertia pulsates."""
    segment: Count | None = None
    """FE models: the [[segment]] (1-based) whose stiffness (or distributed inertia) pulsates."""
    point: Count | None = None
    """FE models: the [[point]] (1-based) whose spring k, kr (or mass and inertia) pulsates."""
    depth: Real["1"] = 1.0
    """Relative depth of this term (the chart's eps multiplies it; negative flips the sign)."""
    harmonic: Count = 1
    """Harmonic h of the term: sin(h Omega t + phase)."""
    phase: Real["rad"] = 0.0
    """Phase of the term, rad."""
    label: str = ""
    """Free text naming the term in outputs."""

    @model_validator(mode="after")
    def _one_part(self):
        given = [k for k in ("spring", "body", "segment", "point") if getattr(self, k) is not None]
        if len(given) > 1:
            rule(given[1], getattr(self, given[1]), f"one part per term (this term already names {given[0]} = "
                 f"{getattr(self, given[0])!r}; add another [[analysis.modulation]] for a second part)")
        if self.spring is not None and self.target != "stiffness":
            rule("spring", self.spring, "target = 'stiffness' (a spring has no inertia; use body = .. for an inertia)")
        if self.body is not None and self.target != "inertia":
            rule("body", self.body, "target = 'inertia' (a body has no stiffness; use spring = .. for a stiffness)")
        return self

    @property
    def part_key(self) -> str | None:
        """The key naming the pulsating part, or None (the whole matrix)."""
        return next((k for k in ("spring", "body", "segment", "point") if getattr(self, k) is not None), None)


class ParametricAnalysis(Table):
    """``[analysis] type = "parametric"``: Floquet stability chart of the linear model with periodic stiffness
    and/or inertia (textbook ch. 7, Fig. 7.4): max |multiplier| over the (eps, Omega) grid, the tongue edges at
    chosen depths and the damping thresholds eps* of the principal tongues.  Damping: the [damping] table and
    the model's dampers and psi values (psi -> zeta = psi / (4 pi), (7.31))."""

    type: Literal["parametric"]
    modulation: Annotated[list[Modulation], Field(min_length=1)]
    """[[analysis.modulation]]: the pulsating terms (at least one)."""
    omega_rad_s: OmegaGrid | None = None
    """Excitation frequencies Omega: { start, stop, points }, rad/s."""
    omega_ratio: OmegaRatioGrid | None = None
    """Excitation frequencies as Omega / omega_1 (first natural frequency of the mean system): { start, stop, points }."""
    depth: DepthGrid
    """Depths of pulsation eps: { max, min = 0, points = 41 }."""
    boundaries_at: list[NonNegative["1"]] = []
    """Depths at which the tongue edges are located by root finding."""
    boundary_samples: Integer(ge=2) = 401
    """Omega samples of each edge search (thin tongues between samples are searched too)."""
    thresholds: bool = True
    """Damping thresholds eps* of the principal tongues Omega = 2 omega_r inside the Omega range."""
    inertia_form: Literal["programme", "momentum", "newton"] = "programme"
    """Equation of a pulsating inertia: 'programme' (7.7) M q'' + (C + M') q' + (K + M''/2) q = 0, 'momentum'
    (M q')' + C q' + K q = 0, 'newton' M q'' + C q' + K q = 0."""
    modes: Count | None = None
    """Project on the lowest modes of the mean system (required above 60 free DOFs)."""
    tolerance: Number(gt=0, le=1e-4)["1"] = 1e-10
    """Relative error target of each monodromy matrix (step doubling of the sixth-order Magnus integrator)."""
    stability_margin: Number(gt=0, le=1e-2)["1"] = 1e-6
    """A point is stable if max |multiplier| < 1 + stability_margin."""

    @model_validator(mode="after")
    def _grid(self):
        keys = [k for k in ("omega_rad_s", "omega_ratio") if getattr(self, k) is not None]
        if len(keys) != 1:
            rule("omega_rad_s", keys or None, "exactly one of omega_rad_s = { start, stop, points } (rad/s) or "
                 "omega_ratio = { start, stop, points } (Omega / omega_1)")
        for d in self.boundaries_at:
            if d > self.depth.max:
                rule("boundaries_at", self.boundaries_at, f"depths <= depth.max = {self.depth.max}")
        return self


def _analysis_type(v) -> str:
    return v.get("type", "modal") if isinstance(v, dict) else getattr(v, "type", "modal")


Analysis = Annotated[Union[Annotated[ModalAnalysis, Tag("modal")], Annotated[ForcedAnalysis, Tag("forced")],
                           Annotated[ParametricAnalysis, Tag("parametric")]],
                     Discriminator(_analysis_type)]


DAMPING_KEYS = {"rayleigh": ("alpha", "beta"), "modal": ("zeta",), "hysteretic": ("psi",), "viscous": (), "none": ()}


class Damping(Table):
    """``[damping]``: global damping on top of the model's own dampers and psi values.

    type = "viscous" (default without keys): the model's own dampers only; "rayleigh": + alpha M +
    beta K; "modal": + modal ratio zeta in every mode (modal superposition); "hysteretic": + complex
    stiffness psi on every stiffness; "none": no damping at all.  Without ``type`` the keys given
    decide it (alpha/beta: rayleigh, zeta: modal, psi: hysteretic)."""

    type: Literal["none", "viscous", "rayleigh", "modal", "hysteretic"] | None = None
    """Damping model (default: from the keys given, else "viscous")."""
    alpha: NonNegative["1/s"] = 0.0
    """Rayleigh mass-proportional coefficient, 1/s."""
    beta: NonNegative["s"] = 0.0
    """Rayleigh stiffness-proportional coefficient, s."""
    zeta: NonNegative["1"] = 0.0
    """Modal damping ratio."""
    psi: NonNegative["1"] = 0.0
    """Dissipation coefficient of the textbook (delta = psi / (4 pi))."""
    psi_time: Literal["equivalent", "modal"] | None = None
    """Time domain: how psi (of [damping], segments and springs) becomes a viscous matrix: "equivalent"
    (9.3) C = H / omega_ref, or "modal" (9.14)-(9.18) (default: equivalent at the single forcing frequency,
    else modal)."""
    omega_ref: Positive["rad/s"] | Literal["forcing", "first_mode"] | None = None
    """Time domain, psi_time = "equivalent": the reference frequency, rad/s, "forcing" or "first_mode"."""
    psi_modes: Count | None = None
    """Time domain, psi_time = "modal": modes of the modal dissipation (default: all up to 200 DOFs, else 20)."""
    psi_completion: Literal["stiffness", "none"] = "stiffness"
    """Time domain, psi_time = "modal": the modes not included get the stiffness-proportional remainder, or none."""

    @model_validator(mode="after")
    def _keys_match(self):
        if self.omega_ref is not None and self.psi_time == "modal":
            rule("omega_ref", self.omega_ref, "only with psi_time = 'equivalent'")
        for key in ("psi_modes", "psi_completion"):
            if self.given(key) and self.psi_time == "equivalent":
                rule(key, getattr(self, key), "only with psi_time = 'modal'")
        given = [k for k in ("alpha", "beta", "zeta", "psi") if self.given(k)]
        kind = self.kind
        for k in given:
            if k not in DAMPING_KEYS[kind]:
                owner = next(t for t, keys in DAMPING_KEYS.items() if k in keys)
                rule(k, getattr(self, k), f"only with type = {owner!r} (this table: type = {kind!r})")
        if self.type is None and len({next(t for t, ks in DAMPING_KEYS.items() if k in ks) for k in given}) > 1:
            rule("type", None, "one damping model: 'rayleigh' (alpha, beta) | 'modal' (zeta) | 'hysteretic' (psi)")
        return self

    @property
    def kind(self) -> str:
        """The damping model, explicit or implied by the keys."""
        if self.type is not None:
            return self.type
        for t, keys in DAMPING_KEYS.items():
            if any(self.given(k) for k in keys):
                return t
        return "viscous"


class Excitation(Table):
    """Location keys shared by ``[[load]]``, ``[[base_motion]]`` and ``[[response]]``."""

    x: Real["m"] | None = None
    """FE models: node position, m."""
    dof: str | None = None
    """FE models: DOF name at the node (default: the primary field)."""
    body: Annotated[str, Field(min_length=1)] | None = None
    """Lumped models: body name."""

    @model_validator(mode="after")
    def _one_place(self):
        if self.x is not None and self.body is not None:
            rule("body", self.body, "either x = .. (FE node) or body = .. (lumped body), not both")
        if self.dof is not None and self.x is None:
            rule("dof", self.dof, "only with x = .. (an FE node)")
        return self


class Waveform(Table):
    """A periodic load's shape over one period (``[analysis] period``): the load is amplitude * w(t/T +
    phase_deg/360) with the unit shape w: "square" (+1 for a fraction duty of the period, then -1),
    "sawtooth" (2 s - 1), "triangle" (1 - 4 |s - 1/2|) or "table" (piecewise linear through t, value)."""

    kind: Literal["square", "sawtooth", "triangle", "table"]
    """The unit shape."""
    duty: Number(gt=0, lt=1)["1"] | None = None
    """square: the fraction of the period at +1 (default 0.5)."""
    t: Annotated[list[Real["1"]], Field(min_length=2)] | None = None
    """table: instants as fractions of the period, increasing from 0 to 1."""
    value: Annotated[list[Real["1"]], Field(min_length=2)] | None = None
    """table: the shape's values at t (value[0] == value[-1])."""

    @model_validator(mode="after")
    def _shape(self):
        if self.duty is not None and self.kind != "square":
            rule("duty", self.duty, 'only with kind = "square"')
        if self.kind == "table":
            if self.t is None or self.value is None:
                rule("t", self.t, 'kind = "table" needs t = [0, .., 1] (fractions of the period) and value = [..]')
            if len(self.t) != len(self.value):
                rule("value", f"{len(self.value)} values", f"one value per t ({len(self.t)})")
            if self.t[0] != 0 or self.t[-1] != 1 or any(b <= a for a, b in zip(self.t, self.t[1:])):
                rule("t", self.t, "fractions of the period increasing from 0 to 1")
            if abs(self.value[0] - self.value[-1]) > 1e-12 * max(1.0, max(map(abs, self.value))):
                rule("value", [self.value[0], self.value[-1]], "value[0] == value[-1] (one period)")
        elif self.t is not None or self.value is not None:
            rule("t" if self.t is not None else "value", self.t if self.t is not None else self.value,
                 'only with kind = "table"')
        return self


class Load(Excitation):
    """``[[load]]``: harmonic force amplitude * exp(i phase) at a DOF (forced analysis), or with a
    ``waveform`` a periodic non-harmonic load of the period ``[analysis] period``."""

    unit_choice: ClassVar[dict] = {"amplitude": ("scaling", {"constant": (0, 1), "omega2": (2, 3)})}

    amplitude: Real["N", "N*m", "kg*m", "kg*m^2*rad"]
    """Force or moment amplitude (N or N m; with scaling = "omega2": m e, kg m, or its rotational analogue)."""
    phase_deg: Real["deg"] = 0.0
    """Phase, degrees (with a waveform: the shift of its period, 360 = one period)."""
    waveform: Waveform | None = None
    """A periodic non-harmonic shape { kind = "square" | "sawtooth" | "triangle" | "table", .. }."""
    scaling: Literal["constant", "omega2"] = "constant"
    """"omega2": a load proportional to the frequency squared, amplitude * omega^2 -- an unbalance with
    amplitude = m e (kg m; textbook §5.12, §6.4); "constant": amplitude as given."""

    @model_validator(mode="after")
    def _scaling(self):
        if self.scaling == "omega2" and self.waveform is not None:
            rule("scaling", self.scaling, '"constant" with a waveform (a periodic load has one shape)')
        return self


class BaseMotion(Table):
    """``[[base_motion]]``: harmonic motion of a held DOF (a clamped/pinned support or a driver)."""

    x: Real["m"] | None = None
    """FE models: position of the moving support, m."""
    dof: str | None = None
    """FE models: DOF of the support."""
    driver: Annotated[str, Field(min_length=1)] | None = None
    """Lumped models: driver name."""
    amplitude: Real["m", "rad"]
    """Displacement amplitude."""
    phase_deg: Real["deg"] = 0.0
    """Phase, degrees."""

    @model_validator(mode="after")
    def _one_place(self):
        if self.x is not None and self.driver is not None:
            rule("driver", self.driver, "either x = .. (FE support) or driver = .. (lumped driver), not both")
        return self


class Response(Excitation):
    """``[[response]]``: an output DOF of the forced analysis."""
