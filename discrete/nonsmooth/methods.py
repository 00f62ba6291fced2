"""One entry for the three time integrators of a nonsmooth problem: the exact event-driven solver
(``"event"``), Moreau-Jean time stepping (``"moreau"``) and the regularised integrator
(``"regularised"``), each with its own settings (the ``[simulation]`` keys of docs/discrete.md)."""
from __future__ import annotations

import numpy as np

from ..errors import ModelError
from .problem import ProblemSpec

METHODS = ("event", "moreau", "regularised")
EVENT_KEYS = ("max_events", "max_step", "steps_per_period", "rtol", "rest_tol", "energy", "output_step", "progress",
              "max_evaluations")
REGULARISED_KEYS = ("regularisation", "penalty", "memory_time", "rtol", "max_step")
MOREAU_KEYS = ("dt", "theta", "tol", "max_iter", "max_events")


def simulate_spec(spec: ProblemSpec, t_end: float, method: str = "event", settings: dict | None = None,
                  problem=None):
    """Integrate ``spec`` to ``t_end`` with ``method``; ``settings`` holds the method's options
    (and ``samples`` for the time stepper's output); ``problem``: ``spec.problem()`` if already
    built.  Returns the method's result."""
    settings = dict(settings or {})
    if method == "event":
        from .solver import Options, simulate

        opts = Options(**{k: settings[k] for k in EVENT_KEYS if k in settings})
        return simulate(problem or spec.problem(), t_end, opts)
    if method == "regularised":
        from .regularised import simulate_regularised

        return simulate_regularised(problem or spec.problem(), t_end,
                                    **{k: settings[k] for k in REGULARISED_KEYS if k in settings})
    if method == "moreau":
        from ..timestepping import StepOptions, simulate_timestepping

        if spec.mass_rate is not None and np.any(np.asarray(spec.mass_rate)):
            raise ModelError("[simulation]", "method", "moreau", "'event' for variable mass (inertia_rate != 0): "
                             "the Moreau-Jean stepper factorises a constant iteration matrix")
        opts = StepOptions(dt=settings["dt"], theta=settings.get("theta", 0.5), tol=settings.get("tol", 1e-10),
                           max_iter=settings.get("max_iter", 2000), max_events=settings.get("max_events", 100_000),
                           progress=settings.get("progress"))
        n_steps = int(np.ceil(t_end / opts.dt))
        opts.sample_every = max(1, n_steps // settings.get("samples", 2000))
        return simulate_timestepping(spec.system, spec.elements, drivers=spec.drivers, forces=spec.forces,
                                     x0=spec.x0, v0=spec.v0, t_end=t_end, options=opts)
    raise ModelError("[simulation]", "method", method, " | ".join(map(repr, METHODS)))
