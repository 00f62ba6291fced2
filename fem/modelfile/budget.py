"""Size and cost limits, checked before any work starts: a model file can ask for more work than a
machine can do (1e9 elements, 1e300 s of simulated time, 1e-300 s steps); that is a clear error
naming the key and the estimated cost, never a hang or a MemoryError.

The limits are generous for real models (the largest example asks for a few per cent of any of
them); a deliberate larger run raises them all with the environment variable ``DRIVEFEM_BUDGET``
(a factor, e.g. ``DRIVEFEM_BUDGET=10``)."""
from __future__ import annotations

import math
import os

from discrete.errors import ModelError

MAX_FE_DOFS = 2_000_000          # FE unknowns (sparse factorisation memory)
MAX_DRIVE_N = 200_000            # mechanisms of a drive of regular structure
MAX_MODES = 5_000                # eigenpairs asked for
MAX_FREQUENCIES = 100_000        # frequencies of a harmonic analysis
MAX_HB_UNKNOWNS = 20_000         # harmonic-balance unknowns (dense Jacobian)
MAX_HB_SAMPLES = 200_000         # AFT time samples per period
MAX_CONTINUATION_STEPS = 100_000
MAX_TIME_STEPS = 5_000_000       # steps of a time integration (estimated)
MAX_START_STEPS = 100_000        # steps of the DOP853 run that starts HB ([steady] start = "time"; Python rhs)
MAX_OUTPUT_SAMPLES = 2_000_000   # recorded instants of a simulation
MAX_RECORDED_VALUES = 100_000_000  # numbers a time integration keeps in memory (every step end x state size)
MAX_RESPONSE_VALUES = 50_000_000   # complex amplitudes a harmonic analysis keeps (frequencies x DOFs, samples x outputs)
MAX_NUMERIC_EVALUATIONS = 500_000  # right-hand sides of the numeric pieces of an event-driven run (checked as it runs)


def numeric_evaluations() -> int:
    """The right-hand-side evaluations the numerically integrated pieces of an event-driven run may use: their
    cost shows only while they run (a stiff law makes DOP853's steps tiny), so the solver stops the run when
    they are used up (exit 1, results up to there kept)."""
    return int(MAX_NUMERIC_EVALUATIONS * scale())


def scale() -> float:
    """The budget factor of ``DRIVEFEM_BUDGET`` (default 1)."""
    raw = os.environ.get("DRIVEFEM_BUDGET", "1")
    try:
        f = float(raw)
    except ValueError:
        f = float("nan")
    if not (f > 0 and math.isfinite(f)):
        raise ModelError("environment", "DRIVEFEM_BUDGET", raw, "a number > 0 (a factor on every size limit)")
    return f


def check_count(where: str, key, estimate: float, limit: float, what: str, value=None) -> None:
    """Refuse ``estimate`` (a number of ``what`` implied by ``key = value``) above ``limit`` times the
    budget factor."""
    lim = limit * scale()
    if not (estimate <= lim):          # also NaN and infinity
        shown = f"{estimate:.3g}" if math.isfinite(estimate) else "unbounded"
        factor = estimate / limit if math.isfinite(estimate) else float("inf")
        raise ModelError(where, key, estimate if value is None else value,
                         f"a value implying at most {lim:.3g} {what} (this one: {shown}); a deliberate larger run "
                         f"needs DRIVEFEM_BUDGET >= {factor:.3g}")


def check_document(doc, kind: str) -> None:
    """The limits that follow from the file alone (sizes), before anything is built."""
    if kind in ("fe", "hybrid"):
        fields = 2 if doc.model.physics == "bending" else 1
        order = 1 if (doc.model.physics == "bending" and doc.model.theory == "euler-bernoulli") else doc.model.order
        dofs = sum(s.elements for s in doc.segment) * order * fields
        check_count("[[segment]]", "elements", dofs, MAX_FE_DOFS, "FE unknowns", [s.elements for s in doc.segment])
    if kind == "drive":
        n = doc.drive.n
        conv = getattr(doc.analysis, "convergence_n", None) or []
        check_count("[drive]", "n", max([n] + list(conv)), MAX_DRIVE_N, "mechanisms", n)
        co = getattr(doc.drive, "continuum", None)
        if co is not None:
            check_count("[drive.continuum]", "elements", 2 * co.order * co.elements, MAX_FE_DOFS,
                        "FE unknowns of the pseudo-medium", co.elements)
    an = doc.analysis
    if an is not None and an.modes is not None:
        check_count("[analysis]", "modes", an.modes, MAX_MODES, "modes")
    if getattr(an, "sweep_hz", None) is not None:
        check_count("[analysis.sweep_hz]", "points", an.sweep_hz.points, MAX_FREQUENCIES, "frequencies")
    st = getattr(doc, "steady", None)
    if st is not None:
        check_count("[steady]", "max_steps", st.max_steps, MAX_CONTINUATION_STEPS, "continuation steps")
        check_count("[steady]", "harmonics", 2 * st.harmonics + 1, MAX_HB_UNKNOWNS, "Fourier coefficients per DOF")
        if st.samples is not None:
            check_count("[steady]", "samples", st.samples, MAX_HB_SAMPLES, "time samples per period")
    sim = getattr(doc, "simulation", None)
    if sim is not None:
        t = sim.t_end
        if sim.max_step is not None:
            check_count("[simulation]", "max_step", t / sim.max_step, MAX_TIME_STEPS, "steps (t_end / max_step)",
                        sim.max_step)
        if sim.output_step is not None:
            check_count("[simulation]", "output_step", t / sim.output_step, MAX_OUTPUT_SAMPLES,
                        "output samples (t_end / output_step)", sim.output_step)
        if sim.dt is not None:
            check_count("[simulation]", "dt", t / sim.dt, MAX_TIME_STEPS, "steps (t_end / dt)", sim.dt)
        if sim.samples is not None:
            check_count("[simulation]", "samples", sim.samples, MAX_OUTPUT_SAMPLES, "output samples")
        if sim.max_events is not None:
            # every event records the states before and after it, and an event record: a run that
            # used its whole allowance would hold 2 max_events samples (measured: 1e8 allowed
            # events filled 23 GB within minutes, seed 000 at ~40 000 events/s)
            check_count("[simulation]", "max_events", 2 * sim.max_events, MAX_OUTPUT_SAMPLES,
                        "recorded instants (two per event, kept in memory)", sim.max_events)


def check_time_integration(t_end: float, omega_max: float, steps_per_period: int, method: str,
                           state_size: int = 1) -> None:
    """The steps an event-driven or regularised run needs to resolve its fastest motion over ``t_end``:
    ``omega_max`` is the highest frequency of the linear part with the stiffest element, or the fastest rate
    of its dampers and of an element's own dynamics (a motor's time constant), whichever is larger
    (:attr:`discrete.nonsmooth.problem.Problem.rate_max`); the memory of the run is those steps times
    ``state_size`` (the solvers keep every step's state)."""
    if method == "moreau":
        return                            # fixed step: checked from dt
    steps = t_end * omega_max * steps_per_period / (2 * math.pi)
    check_count("[simulation]", "t_end", steps, MAX_TIME_STEPS,
                f"steps ({steps_per_period} per period of the highest frequency or fastest rate {omega_max:.3g} rad/s of the "
                "model: stiff elements, small inertias, strong dampers or short motor time constants shorten it)",
                t_end)
    # every step end is recorded (the event-driven solver keeps the state at each step; DOP853 its steps)
    check_count("[simulation]", "t_end", steps * max(1, state_size), MAX_RECORDED_VALUES,
                f"recorded values ({steps:.3g} steps x {state_size} state variables, kept in memory)", t_end)


def check_start_integration(t_end: float, omega_max: float, periods: int) -> None:
    """[steady] start = "time": the steps of the DOP853 run that gives harmonic balance its start
    (about 16 per period of the model's highest frequency over start_periods response periods)."""
    steps = t_end * omega_max * 16 / (2 * math.pi)
    check_count("[steady]", "start_periods", steps, MAX_START_STEPS,
                f"integration steps for the start (16 per period of the highest frequency {omega_max:.3g} rad/s "
                "over start_periods x subharmonic forcing periods)", periods)


def check_hb(n_dofs: int, harmonics: int, key: str = "harmonics") -> None:
    """The HB unknowns n_dofs (2 harmonics + 1) within the budget (``key``: the key that sets them)."""
    check_count("[steady]", key, n_dofs * (2 * harmonics + 1), MAX_HB_UNKNOWNS,
                f"harmonic-balance unknowns ({n_dofs} DOFs x (2 harmonics + 1))")


def check_response(n_frequencies: int, n_dofs: int, n_outputs: int, harmonics: int | None = None) -> None:
    """The memory of a linear forced analysis: the complex amplitudes of every DOF at every frequency (the
    direct solver keeps them), and with a periodic load the period sampled for its peak (max(8192, 32 H)
    instants per output, discrete.linear.periodic_forced)."""
    if harmonics is None:
        check_count("[analysis]", "frequencies", n_frequencies * n_dofs, MAX_RESPONSE_VALUES,
                    f"response values ({n_frequencies} frequencies x {n_dofs} DOFs, kept in memory)", n_frequencies)
        return
    samples = max(8192, 32 * harmonics)
    check_count("[analysis]", "harmonics", max((harmonics + 1) * n_dofs, samples * n_outputs), MAX_RESPONSE_VALUES,
                f"response values (({harmonics} + 1) harmonics x {n_dofs} DOFs, and {samples} samples of a period x "
                f"{n_outputs} outputs, kept in memory)", harmonics)
