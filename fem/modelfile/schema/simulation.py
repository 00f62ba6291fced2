"""Tables of the time simulation: ``[simulation]``, ``[constants]``, ``[initial]`` and ``[reduction]``.
One ``[simulation]`` table for every kind of file; ``method`` picks the integrator."""

from typing import Annotated, Literal

from pydantic import Field, model_validator

from .base import Count, Number, Positive, Real, Table, rule

METHOD_KEYS = {"event": ("max_events", "max_step", "steps_per_period", "rtol", "rest_tol", "output_step"),
               "regularised": ("regularisation", "penalty", "memory_time", "rtol", "max_step"),
               "moreau": ("dt", "theta", "tol", "max_iter", "max_events")}
COMMON_KEYS = ("t_end", "method", "energy", "samples", "record_every")


class Simulation(Table):
    """``[simulation]``: time integration from t = 0 to ``t_end``."""

    t_end: Positive["s"]
    """End time, s."""
    method: Literal["event", "moreau", "regularised"] = "event"
    """"event": exact event-driven (true stick, exact pieces); "moreau": Moreau-Jean time stepping;
    "regularised": smooth friction/penalty contacts with an adaptive integrator."""
    energy: bool = True
    """Energy balance of the run (reported as energy_error)."""
    samples: Count | None = None
    """Hybrid models: number of sampled field snapshots in the output (default 2000)."""
    max_events: Count | None = None
    """Event limit (event: 200000, moreau: 100000); reaching it stops the run, keeping what was computed."""
    max_step: Positive["s"] | None = None
    """Largest step of the numeric pieces / exact-piece marching, s."""
    steps_per_period: Count | None = None
    """Event solver: marching steps per period of the highest frequency (default 12)."""
    rtol: Positive["1"] | None = None
    """Relative tolerance of numerically integrated pieces (default 1e-12; regularised 1e-9)."""
    rest_tol: Positive["1"] | None = None
    """Event solver: impact accumulation threshold, rebound speed / largest impact speed (default 1e-9)."""
    output_step: Positive["s"] | None = None
    """Event solver: extra exact output samples every output_step seconds (plots, CSV)."""
    regularisation: Positive["m/s", "rad/s"] | None = None
    """Regularised: velocity scale of the smoothed friction law."""
    penalty: Positive["N/m", "N*m/rad"] | None = None
    """Regularised: penalty stiffness of rigid stops."""
    memory_time: Positive["s"] | None = None
    """Regularised: time constant of the friction memory state."""
    dt: Positive["s"] | None = None
    """Moreau-Jean: time step, s (required for method = "moreau")."""
    theta: Number(ge=0.5, le=1)["1"] | None = None
    """Moreau-Jean: theta of the theta-method (default 0.5)."""
    tol: Positive["1"] | None = None
    """Moreau-Jean: tolerance of the contact/friction projections (default 1e-10)."""
    max_iter: Count | None = None
    """Moreau-Jean: iteration limit of the projections (default 2000)."""
    record_every: Count = 1
    """Write every record_every-th recorded sample of the time history (CSV, --h5, plots); event instants
    are always written, and the summaries (peak, rms, ...) use every sample."""

    @model_validator(mode="after")
    def _method_keys(self):
        for key, owners in {k: [m for m, ks in METHOD_KEYS.items() if k in ks]
                            for ks in METHOD_KEYS.values() for k in ks}.items():
            if getattr(self, key) is not None and self.method not in owners:
                rule(key, getattr(self, key), "only with method = " + " | ".join(repr(m) for m in owners))
        if self.method == "moreau" and self.dt is None:
            rule("dt", None, "a time step dt = .. for method = \"moreau\" (required key missing)")
        return self

    def options(self) -> dict:
        """The settings given for the chosen method (name -> value), without defaults."""
        return {k: getattr(self, k) for k in METHOD_KEYS[self.method] + ("energy", "samples")
                if getattr(self, k) is not None and self.given(k)}


class Constants(Table):
    """``[constants]``: physical constants."""

    g: Positive["m/s^2"] = 9.81
    """Gravitational acceleration, m/s^2."""


class Initial(Table):
    """``[initial]`` (hybrid models): the initial state of the FE field."""

    velocity: Real["m/s", "rad/s"] = 0.0
    """Uniform velocity of the primary field (a rigid translation/rotation), m/s or rad/s."""
    state: Literal["rest", "linear_steady_state"] = "rest"
    """"rest", or the steady state of the linear FE model under the harmonic [[force]] tables."""


class Reduction(Table):
    """``[reduction]`` (hybrid models): modal reduction of the FE part (Craig-Bampton with the element
    DOFs kept physical, or free-interface modes)."""

    modes: Count
    """Number of retained modes."""
    static_correction: bool = True
    """Craig-Bampton (static shapes of the coupling DOFs) or free-interface modes only."""
    threshold: Number(gt=0, le=1)["1"] = 0.95
    """Restitution share at every coupling DOF below which a warning is given."""
