"""Tables of the linear analyses: ``[analysis]`` (modal or forced), ``[damping]``, ``[[load]]``,
``[[base_motion]]`` and ``[[response]]``.  ``[damping]`` has one meaning in every kind of file:
the global damping added to the model's own dampers and dissipation coefficients (design.md §3)."""
from __future__ import annotations

from typing import Annotated, Literal, Union

from pydantic import Discriminator, Field, Tag, model_validator

from .base import Count, NonNegative, Positive, Table, rule


class SweepHz(Table):
    """A frequency grid in Hz."""

    start: NonNegative
    """First frequency, Hz."""
    stop: Positive
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
    shift: float | None = None
    """Shift of the shift-invert eigensolver, rad^2/s^2 (default: automatic)."""
    tolerance: Annotated[float, Field(gt=0, lt=1)] = 1e-5
    """Relative residual above which a mode is reported as not reliable."""
    convergence_n: Annotated[list[Count], Field(min_length=1)] | None = None
    """Drive files: mechanism counts n of the convergence study towards the pseudo-medium."""


class ForcedAnalysis(Table):
    """``[analysis] type = "forced"``: harmonic response over a frequency list (linear models), or
    the amplitude-frequency curve of the ``[steady]`` table (nonlinear models)."""

    type: Literal["forced"]
    frequencies_hz: Annotated[list[NonNegative], Field(min_length=1)] | None = None
    """Forcing frequencies, Hz."""
    omega_rad_s: Annotated[list[NonNegative], Field(min_length=1)] | None = None
    """Forcing angular frequencies, rad/s."""
    sweep_hz: SweepHz | None = None
    """A grid: { start, stop, points, spacing = "linear" | "log" }, Hz."""
    method: Literal["direct", "modal"] = "direct"
    """Direct sparse solve per frequency, or modal superposition."""
    modes: Count | None = None
    """Modes of the modal superposition (default min(20, free DOFs))."""
    convergence_n: Annotated[list[Count], Field(min_length=1)] | None = None
    """Drive files: mechanism counts n of the convergence study."""

    @property
    def frequency_keys(self) -> list[str]:
        return [k for k in ("frequencies_hz", "omega_rad_s", "sweep_hz") if getattr(self, k) is not None]


def _analysis_type(v) -> str:
    return v.get("type", "modal") if isinstance(v, dict) else getattr(v, "type", "modal")


Analysis = Annotated[Union[Annotated[ModalAnalysis, Tag("modal")], Annotated[ForcedAnalysis, Tag("forced")]],
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
    alpha: NonNegative = 0.0
    """Rayleigh mass-proportional coefficient, 1/s."""
    beta: NonNegative = 0.0
    """Rayleigh stiffness-proportional coefficient, s."""
    zeta: NonNegative = 0.0
    """Modal damping ratio."""
    psi: NonNegative = 0.0
    """Dissipation coefficient of the textbook (delta = psi / (4 pi))."""
    psi_time: Literal["equivalent", "modal"] | None = None
    """Time domain: how psi (of [damping], segments and springs) becomes a viscous matrix: "equivalent"
    (9.3) C = H / omega_ref, or "modal" (9.14)-(9.18) (default: equivalent at the single forcing frequency,
    else modal)."""
    omega_ref: Positive | Literal["forcing", "first_mode"] | None = None
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

    x: float | None = None
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


class Load(Excitation):
    """``[[load]]``: harmonic force amplitude * exp(i phase) at a DOF (forced analysis)."""

    amplitude: float
    """Force or moment amplitude."""
    phase_deg: float = 0.0
    """Phase, degrees."""


class BaseMotion(Table):
    """``[[base_motion]]``: harmonic motion of a held DOF (a clamped/pinned support or a driver)."""

    x: float | None = None
    """FE models: position of the moving support, m."""
    dof: str | None = None
    """FE models: DOF of the support."""
    driver: Annotated[str, Field(min_length=1)] | None = None
    """Lumped models: driver name."""
    amplitude: float
    """Displacement amplitude."""
    phase_deg: float = 0.0
    """Phase, degrees."""

    @model_validator(mode="after")
    def _one_place(self):
        if self.x is not None and self.driver is not None:
            rule("driver", self.driver, "either x = .. (FE support) or driver = .. (lumped driver), not both")
        return self


class Response(Excitation):
    """``[[response]]``: an output DOF of the forced analysis."""
