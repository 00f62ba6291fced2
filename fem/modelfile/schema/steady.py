"""``[steady]`` (nonlinear amplitude-frequency curves) and ``[sweep]`` (parameter maps on Dask)."""

from typing import Annotated, Literal, Union

from pydantic import Field, model_validator

from .base import SWEPT, Count, Integer, Number, Positive, Table, rule


class ResponseMeasure(Table):
    """What the curve shows: a body's coordinate or an element's force along its coordinate."""

    body: Annotated[str, Field(min_length=1)] | None = None
    """A free body (default: the first free DOF)."""
    element: Annotated[str, Field(min_length=1)] | None = None
    """A spring-like element: the magnitude of its force (tension of a strand)."""
    measure: Literal["amplitude", "max", "min", "peak", "h1"] = "amplitude"
    """Half peak-to-peak, max, min, max |.|, or the amplitude at the forcing frequency."""
    scale: Positive["m", "rad", "N", "N*m"] = 1.0
    """The measure is divided by scale (e.g. F0 for a dynamic factor)."""

    @model_validator(mode="after")
    def _one(self):
        if self.body is not None and self.element is not None:
            rule("element", self.element, "not together with body")
        return self


FrequencyRange = Annotated[list[Positive["rad/s"]], Field(min_length=2, max_length=2)]
RatioRange = Annotated[list[Positive["1"]], Field(min_length=2, max_length=2)]


class Steady(Table):
    """``[steady]``: periodic steady states continued in the forcing frequency (every harmonic
    [[driver]] and [[force]] is set to it)."""

    method: Literal["hb", "shooting"] = "hb"
    """Harmonic balance with AFT, or shooting with the exact event-driven integrator."""
    omega: FrequencyRange | None = None
    """[start, stop] forcing frequency range, rad/s (continued from start to stop)."""
    z: RatioRange | None = None
    """[start, stop] ratio range z = omega / omega_ref."""
    omega_ref: Positive["rad/s"] | None = None
    """Reference frequency of z, rad/s."""
    harmonics: Count = 7
    """HB: number of harmonics."""
    subharmonic: Integer(ge=1, le=20) = 1
    """Orbits of period subharmonic * 2 pi / omega."""
    samples: Count | None = None
    """HB: AFT time samples per period (at least 4 H + 2; default max(64, 8 H + 4), with sampled friction
    max(1024, 16 H), with sampled kinks max(256, 16 H))."""
    regularisation: Positive["m/s", "rad/s"] = 1e-3
    """HB: friction sign(w) ~ tanh(w / regularisation)."""
    response: ResponseMeasure = ResponseMeasure()
    """The plotted response: { body = .. } or { element = .., measure = .., scale = .. }."""
    stability: bool = True
    """Floquet multipliers (HB: variational equation; shooting: monodromy)."""
    ds: Positive["1"] = 0.02
    """Initial arc-length step (scaled)."""
    ds_max: Positive["1"] = 0.1
    """Largest arc-length step."""
    ds_min: Positive["1"] = 1e-5
    """Smallest arc-length step (the continuation stops below it)."""
    max_steps: Count = 2000
    """Continuation step limit."""
    steps_per_period: Count = 48
    """Shooting: step limit of the event-driven integrator per period."""
    start: Literal["linear", "time"] = "linear"
    """HB: the first point from the "linear" guess, or from a "time" integration of start_periods periods
    starting at the bodies' x0/v0 (the way onto a subharmonic branch, textbook §8.4)."""
    start_periods: Integer(ge=1, le=5_000) = 100
    """HB, start = "time": response periods (forcing periods x subharmonic) integrated before HB."""
    backbone: bool = False
    """Also the nonlinear mode through the response DOF (backbone: frequency and damping ratio against
    amplitude, extended periodic motion concept by HB), in the JSON and on the plot."""
    condense: Literal["auto", "yes", "no"] = "auto"
    """HB: solve on the nonlinear elements' DOFs only, the linear rest condensed exactly per harmonic
    (its receptance factorised once per frequency); "auto" where it pays (at most half of the DOFs
    nonlinear and >= 120 HB unknowns), "yes" always (an error if the linear rest is not regular), "no" never."""
    kinks: Literal["exact", "sampled"] = "exact"
    """HB: piecewise-linear laws (gaps, stops, one-sided springs) integrated "exact"ly between their
    crossings, or "sampled" at the AFT samples (the kink then makes the branch zig-zag near resonance)."""
    truncation_tol: Number(gt=0, lt=1)["1"] = 1e-3
    """HB: tolerance of the relative truncation estimate of every point and of the frequency change of
    every fold and bifurcation with more harmonics (docs/steady.md); the run says where it is exceeded."""
    adaptive: bool = False
    """HB: raise the harmonics where the truncation estimate exceeds truncation_tol (up to max_harmonics)."""
    max_harmonics: Count | None = None
    """HB, adaptive: the largest number of harmonics (default 4 x harmonics)."""
    bifurcations: bool = True
    """Classify and locate folds, branch points, period doublings and Neimark-Sacker points (test
    functions of the Floquet multipliers and of the continuation's Jacobian)."""
    switch_branches: bool = False
    """HB: also continue the period-doubled branch of every period doubling and the other branch of every
    branch point (reported as secondary branches)."""

    @model_validator(mode="after")
    def _range(self):
        if (self.omega is None) == (self.z is None):
            rule("omega", self.omega, "exactly one of omega = [start, stop] (rad/s) or z = [start, stop]")
        rng = self.omega if self.omega is not None else self.z
        if rng[0] == rng[1]:
            rule("omega" if self.omega is not None else "z", rng, "a non-empty range (start != stop)")
        if self.z is not None and self.omega_ref is None:
            rule("omega_ref", None, "the reference frequency (rad/s) of z = omega / omega_ref (required key missing)")
        if self.start == "time" and self.method != "hb":
            rule("start", self.start, '"linear" with method = "shooting" (a time start is an HB option)')
        if self.backbone and self.subharmonic != 1:
            rule("backbone", self.backbone, "false with subharmonic > 1 (the mode of the period-1 response)")
        if self.samples is not None and self.samples < 4 * self.harmonics + 2:
            rule("samples", self.samples, f"at least 4 harmonics + 2 = {4 * self.harmonics + 2}")
        if self.max_harmonics is not None and self.max_harmonics < self.harmonics:
            rule("max_harmonics", self.max_harmonics, f"at least harmonics = {self.harmonics}")
        if self.switch_branches and not self.stability:
            rule("switch_branches", True, "stability = true (the bifurcations are found from the Floquet multipliers)")
        if self.method != "hb":
            for key in ("adaptive", "switch_branches"):
                if getattr(self, key):
                    rule(key, True, 'method = "hb" (an HB option)')
        return self

    @property
    def range(self) -> tuple[float, float]:
        """The frequency range in rad/s."""
        if self.omega is not None:
            return float(self.omega[0]), float(self.omega[1])
        return self.z[0] * self.omega_ref, self.z[1] * self.omega_ref


class GridAxis(Table):
    """A sweep axis as a grid."""

    start: Annotated[float, SWEPT]
    """First value, in the unit of the swept key (a plain number; quantity strings: give the axis as a list)."""
    stop: Annotated[float, SWEPT]
    """Last value, in the unit of the swept key."""
    points: Count
    """Number of values."""
    spacing: Literal["linear", "log"] = "linear"
    """Linear or logarithmic spacing."""

    @model_validator(mode="after")
    def _log(self):
        if self.spacing == "log" and (self.start <= 0 or self.stop <= 0):
            rule("start", self.start, "positive start and stop for spacing = 'log'")
        return self


SweepValue = Union[bool, Annotated[int, SWEPT], Annotated[float, SWEPT], str]
Axis = Union[Annotated[list[SweepValue], Field(min_length=1)], GridAxis]


class Sweep(Table):
    """``[sweep]``: a grid or a list of parameter points, each an independent analysis on Dask.
    Keys are dotted paths into the model file: ``table.key`` or ``array.NAME.key`` /
    ``array.INDEX.key`` for arrays of tables."""

    analysis: Literal["steady", "forced", "simulate"] = "steady"
    """Per point: periodic steady state at the point's frequency, the whole AFC of [steady], or the
    time simulation."""
    grid: Annotated[dict[str, Axis], Field(min_length=1)] | None = None
    """Cartesian product of axes (first key slowest): { "path" = [values] or { start, stop, points } }."""
    points: Annotated[list[Annotated[dict[str, SweepValue], Field(min_length=1)]], Field(min_length=1)] | None = None
    """An explicit list of points { "path" = value, .. }."""
    periods: Count = 300
    """"steady": at most this many forcing periods of time integration before shooting."""

    @model_validator(mode="after")
    def _one(self):
        if (self.grid is None) == (self.points is None):
            rule("grid", self.grid, "exactly one of grid = {..} or points = [..]")
        return self
