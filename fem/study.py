"""A model file built once, with every analysis its kind supports: the one object the command line,
the sweeps and the validation catalogue go through (design.md §9).

    study = Study.load("examples/cantilever.toml")      # or Study.parse(dict) / Study(typed_document)
    study.modal(); study.forced(); study.simulate(); study.steady_model()

Kinds: ``fe`` (linear analyses of a shaft), ``lumped`` and ``hybrid`` (linear analyses, time
simulation by the event-driven, Moreau-Jean or regularised integrator, nonlinear steady states),
``drive`` (a drive of regular structure by three representations), ``rotor`` (complex modes at a
speed, Campbell diagram with critical speeds, unbalance response: :mod:`fem.rotor`), ``train`` (geared
multi-shaft trains: complex modes, Campbell diagram, forced response over speed, time simulation with
exact backlash and slip events, nonlinear steady states, Floquet chart of the mesh stiffness:
:mod:`fem.train`, docs/geared.md).
"""
from __future__ import annotations

import warnings
from functools import cached_property
from pathlib import Path

import math

import numpy as np

from discrete.errors import ModelError

from discrete.lazy import lazy_module

from . import modelfile
from .modelfile import budget

# the builders of each kind, loaded when a model of that kind uses them (start-up of the command line:
# a lumped model file does not import scikit-fem, the rotor or the drive packages)
build_drive = lazy_module("fem.modelfile.build.drive")
build_fe = lazy_module("fem.modelfile.build.fe")
build_hybrid = lazy_module("fem.modelfile.build.hybrid")
build_linear = lazy_module("fem.modelfile.build.linear")
build_lumped = lazy_module("fem.modelfile.build.lumped")
build_rotor = lazy_module("fem.modelfile.build.rotor")
build_train = lazy_module("fem.modelfile.build.train")


def steady_settings(table):
    """:func:`fem.modelfile.build.steady.steady_settings` (imported on use: it loads discrete.steady)."""
    from .modelfile.build.steady import steady_settings as build

    return build(table)
from .modelfile.load import kind_of
from .modelfile.plausibility import Plausibility, PlausibilityWarning
from .modelfile.schema.analysis import ForcedAnalysis, ModalAnalysis

DEFAULT_MODES = 6


class Study:
    """One model file, validated once, built lazily, analysed by its kind."""

    damping_report = None
    """How psi became viscous damping in the last time-domain analysis (None: no psi)."""

    def __init__(self, doc, path: Path | None = None):
        self.doc = doc
        self.kind = kind_of(doc)
        self.path = path
        budget.check_document(doc, self.kind)
        self.plausibility = getattr(doc, "__plausibility__", None) or Plausibility()
        """Warnings on values likely in other units than SI or outside the model's theory (at load)."""
        for w in self.plausibility.warnings:
            warnings.warn(w, PlausibilityWarning, stacklevel=2)

    @property
    def model_warnings(self) -> list[str]:
        """The plausibility warnings of the model file (listed first in every JSON ``warnings``)."""
        return list(self.plausibility.warnings)

    @classmethod
    def load(cls, path) -> "Study":
        return cls(modelfile.load(path), Path(path))

    @classmethod
    def parse(cls, doc: dict) -> "Study":
        return cls(modelfile.parse(doc))

    @property
    def title(self) -> str:
        return self.doc.title or (self.path.stem if self.path else "")

    @property
    def analysis(self):
        return self.doc.analysis

    def _need(self, *kinds: str, what: str) -> None:
        if self.kind not in kinds:
            raise ModelError(f"model file ({self.kind})", "kind", self.kind,
                             f"a {' or '.join(kinds)} model for {what}")

    # ------------------------------------------------------------ built models (once)
    @cached_property
    def shaft(self):
        self._need("fe", "hybrid", what="an FE shaft")
        return build_fe.shaft_model(self.doc)

    @cached_property
    def fe_model(self):
        """The assembled FE model (FE files; hybrid files: their FE part)."""
        if self.kind == "hybrid":
            return self.hybrid.fe
        from .assembly import assemble

        self._need("fe", what="an FE model")
        return assemble(self.shaft)

    @cached_property
    def lumped(self):
        self._need("lumped", what="a lumped model")
        return build_lumped.lumped_model(self.doc)

    @cached_property
    def hybrid(self):
        self._need("hybrid", what="a hybrid model")
        return build_hybrid.hybrid_model(self.doc)

    @cached_property
    def compiled(self):
        """The hybrid problem: the (reduced) FE system plus bodies and elements."""
        from .hybrid import compile_hybrid

        return compile_hybrid(self.hybrid)

    @cached_property
    def drive(self):
        self._need("drive", what="a drive of regular structure")
        return build_drive.drive_model(self.doc)

    @cached_property
    def rotor(self):
        """The assembled rotor (:class:`fem.rotor.RotorSystem`) of a rotor file."""
        from .rotor import assemble_rotor

        self._need("rotor", what="a rotor")
        return assemble_rotor(build_rotor.rotor_model(self.doc))

    @cached_property
    def train(self):
        """The assembled train (:class:`fem.train.TrainSystem`) of a train file."""
        from .train import assemble_train

        self._need("train", what="a geared train")
        return assemble_train(build_train.train_model(self.doc))

    def campbell(self, n_modes: int | None = None, progress=None):
        """Rotor and train files: the Campbell diagram of [campbell] with its critical speeds
        (``progress(done, total)`` after each solve: :func:`fem.rotor.campbell`)."""
        from .rotor import campbell

        self._need("rotor", "train", what="drivefem campbell")
        t = self.doc.campbell
        if t is None:
            raise ModelError(f"model file ({self.kind})", "campbell", None, "a table [campbell] with speeds = [..] "
                             "or speeds_rpm = { start, stop, points } (required for drivefem campbell)")
        if self.kind == "train":
            from .train import train_campbell

            tol = self.analysis.tolerance if self.analysis is not None else 1e-6
            return train_campbell(self.train, build_train.speeds(t, "[campbell]"),
                                  build_train.modes_count(self.doc, t, n_modes), orders=tuple(t.orders),
                                  critical=t.critical, tolerance=tol, progress=progress)
        speeds = build_rotor.speed_grid(t, "[campbell]")
        tol = self.analysis.tolerance if self.analysis is not None else 1e-6
        return campbell(self.rotor, speeds, build_rotor.modes_count(self.doc, t, n_modes), orders=tuple(t.orders),
                        critical=t.critical, tolerance=tol, progress=progress)

    def linear_system(self):
        """The linear part: FE assembled, lumped with gears eliminated, hybrid compiled."""
        if self.kind == "fe":
            return self.fe_model.system
        if self.kind == "lumped":
            return self._lumped_system
        if self.kind == "hybrid":
            return self.compiled.system
        if self.kind == "rotor":            # M q'' + (C + Omega G) q' + K q = f at the [analysis] speed
            return self.rotor.system_at(build_rotor.modal_speed(self.doc))
        if self.kind == "train":            # the meshes in their linear state, at the [analysis] speed
            return self.train.system_at(build_train.modal_speed(self.doc))
        raise ModelError("model file (drive)", "drive", "...", "the drive analyses (modal, forced, compare)")

    @cached_property
    def _lumped_system(self):
        return self.lumped.linear_system()

    def compiled_train(self, eliminate_rigid: bool = False):
        """The train's nonsmooth problem at [train] speed (:func:`fem.train.compile.compile_train`): Craig-Bampton
        per shaft by [reduction], [[driver]] motions, [[force]] loads; ``eliminate_rigid`` for steady states."""
        from .train.compile import compile_train

        self._need("train", what="a train's nonsmooth problem")
        key = ("_compiled_train", bool(eliminate_rigid))
        if key not in self.__dict__:
            ts = self.train
            self.__dict__[key] = compile_train(ts, build_train.operating_speed(self.doc),
                                               reduction=build_train.reduction(self.doc),
                                               drivers=build_train.drivers(ts, self.doc),
                                               loads=build_train.loads(ts, self.doc), eliminate_rigid=eliminate_rigid,
                                               start=self.doc.train.start)
        return self.__dict__[key]

    def problem_spec(self, t_end: float | None = None, refuse: bool = True):
        """The nonsmooth problem without its forcing frequency fixed (lumped, hybrid, train)."""
        if self.kind == "lumped":
            return build_lumped.problem_spec(self.doc, t_end, refuse)
        if self.kind == "train":            # steady states: the free rigid-body motion eliminated
            return self.compiled_train(eliminate_rigid=True).spec()
        self._need("hybrid", what="a nonsmooth problem")
        return self.compiled.spec()

    # ------------------------------------------------------------ loads and named outputs (fem.loads)
    linearisation = None
    """What the last linear analysis did with each nonsmooth element (records; None: no element)."""

    @cached_property
    def time_loads(self):
        """The load map of the time simulation (:class:`discrete.loads.DriveLoads`)."""
        from .loads.drive import drive_loads

        self._need("lumped", "hybrid", what="element loads")
        return drive_loads(self)

    @cached_property
    def linear_model(self):
        """The linear analyses' model: every nonsmooth element in its declared linear state
        (:class:`fem.loads.drive.LinearModel`; lumped and hybrid files)."""
        from .loads.drive import LinearModel, drive_loads

        self._need("lumped", "hybrid", what="the linearised elements")
        base = self.linear_system()
        return LinearModel(self, base, drive_loads(self, linear=True, system=base))

    def outputs(self, result):
        """The named outputs of ``result`` (any analysis of this study): element loads, reactions, section
        loads of FE shafts and rotors, [[output]] selections (:func:`fem.loads.study.outputs`; docs/outputs.md):
        a :class:`fem.loads.analyses.NamedOutputs` over modes, frequencies or time, a dict along a [steady]
        curve, or None where the analysis has none (drive files, Campbell diagrams, periodic responses)."""
        from .loads.study import outputs

        return outputs(self, result)

    def steady_model_of(self, result):
        """The steady model behind a [steady] curve computed by :meth:`forced` (built again if not kept)."""
        sm = getattr(self, "_steady", None)
        return sm[1] if sm is not None and sm[0] is result else self.steady_model()

    # ------------------------------------------------------------ analyses
    def modal_count(self, n_modes: int | None = None) -> int:
        """Modes asked for (argument, then [analysis] modes, then 6 capped at the free DOFs)."""
        an = self.analysis
        if n_modes is None and an is not None and an.modes is not None:
            n_modes = an.modes
        if n_modes is not None:
            return n_modes
        if self.kind == "drive":
            return min(DEFAULT_MODES, 2 * self.drive.n)
        system = self.linear_model.system if self.kind in ("lumped", "hybrid") else self.linear_system()
        return max(1, min(DEFAULT_MODES, system.n_free))

    def modal(self, n_modes: int | None = None, shift: float | None = None):
        """Natural frequencies and mode shapes (drive files: by their representation)."""
        if self.kind == "drive":
            from .drives import modal as drive_modal

            self._drive_delta()
            return drive_modal(self.drive, self.modal_count(n_modes))
        if self.kind == "rotor":
            from .rotor import rotor_modes

            tol = self.analysis.tolerance if self.analysis is not None else 1e-6
            return rotor_modes(self.rotor, build_rotor.modal_speed(self.doc),
                               build_rotor.modes_count(self.doc, None, n_modes), tolerance=tol)
        if self.kind == "train":
            from .train import train_modes

            tol = self.analysis.tolerance if self.analysis is not None else 1e-6
            return train_modes(self.train, build_train.modal_speed(self.doc),
                               build_train.modes_count(self.doc, None, n_modes), tolerance=tol)
        from discrete.linear import modal_analysis

        an = self.analysis
        tol = an.tolerance if isinstance(an, ModalAnalysis) else 1e-5
        if shift is None and isinstance(an, ModalAnalysis):
            shift = an.shift
        extra = {}
        if self.plausibility.units_suspect:       # not the mesh: the scales (a warning at load said which)
            extra["precision_advice"] = ("likely cause: values in other units than SI (see the warnings on units "
                                         "above), which put this model's scales far apart -- check them before "
                                         "changing the mesh")
        system = self.linear_system()
        if self.kind in ("lumped", "hybrid"):
            system = self.linear_model.system
            self.linearisation = self.linear_model.records or None
        result = modal_analysis(system, self.modal_count(n_modes), shift=shift, tolerance=tol, **extra)
        motors = [t.name or f"motor{i}" for i, t in enumerate(getattr(self.doc, "motor", None) or (), 1)]
        if motors:
            result.warnings.append(f"the motor(s) {', '.join(motors)} are not part of these undamped modes of the "
                                   "mechanical drive (a motor adds damping, not stiffness or inertia): the drive's "
                                   "eigenvalues with the motor torque as a state are discrete.motion.motor.motor_modes; "
                                   "drivefem forced includes the motor's complex stiffness")
        return result

    def is_steady(self) -> bool:
        """Whether ``forced`` means the nonlinear amplitude-frequency curve of ``[steady]``."""
        return getattr(self.doc, "steady", None) is not None

    def forced(self, progress=None):
        """Harmonic response (linear models), the AFC of [steady] (nonlinear; ``progress(omega)`` at every
        point of the continuation), or the drive's response."""
        an = self.analysis
        if self.is_steady():
            from discrete.linalg import single_threaded_blas
            from discrete.steady import afc

            with single_threaded_blas():     # small dense kernels: BLAS threads only add contention
                sm = self.steady_model()
                res = afc(sm, progress)
                if self.doc.steady.backbone:   # the nonlinear mode through the response DOF (discrete.steady.nnm)
                    from discrete.steady.nnm import afc_backbone

                    res.extra["backbone"] = afc_backbone(sm, res).to_dict()
                self._steady = (res, sm)
                return res
        if self.kind == "train":
            from .train.forced import train_forced

            t = self.doc.forced
            if t is None:
                raise ModelError("model file (train)", "forced", None, "a table [forced] with speeds = .. (the linear "
                                 "response over speed) or [steady] (the nonlinear curve) for drivefem forced")
            ts = self.train
            return train_forced(ts, build_train.speeds(t, "[forced]"), build_train.loads(ts, self.doc),
                                samples=t.samples)
        if self.kind == "rotor":
            from .rotor import unbalance_response

            spec = build_rotor.response_spec(self.doc)
            return unbalance_response(self.rotor, spec.unbalances, spec.speeds, probes=spec.probes,
                                      operating_range=spec.operating_range, find_peaks=spec.find_peaks)
        if not isinstance(an, ForcedAnalysis):
            raise ModelError("[analysis]", "type", getattr(an, "type", None), "'forced' for drivefem forced")
        if self.kind == "drive":
            from .drives import forced as drive_forced

            delta, name = self._drive_delta()
            return drive_forced(self.drive, build_linear.frequencies(an), delta=delta, damping_name=name)
        if self.kind == "hybrid":
            raise ModelError("[analysis]", "type", "forced", "a [steady] table for the forced response of a hybrid "
                             "model (the linear harmonic analysis of FE and lumped files takes [[load]] tables)")
        from discrete.linear import harmonic_response

        system = self.linear_system()
        if self.kind == "lumped":
            system = self.linear_model.system
            self.linearisation = self.linear_model.records or None
        if self.kind == "lumped" and getattr(self.doc, "motor", None):
            system = self._with_motors(system)
        spec = build_linear.forced_spec(self.doc, system)
        budget.check_response(spec.omegas.size, system.n_dofs, len(spec.outputs),
                              spec.harmonics if spec.period is not None else None)
        if spec.period is not None:
            from discrete.linear.periodic_forced import periodic_forced

            return periodic_forced(system, spec.period, spec.harmonics, shaped=spec.waveforms,
                                   force=spec.force if np.any(spec.force) else None, base_motion=spec.base_motion,
                                   damping=build_linear.damping(self.doc.damping), outputs=spec.outputs,
                                   method=spec.method, n_modes=spec.n_modes)
        res = harmonic_response(system, spec.omegas, force=spec.force, force_omega2=spec.force_w2,
                                base_motion=spec.base_motion, damping=build_linear.damping(self.doc.damping),
                                outputs=spec.outputs, method=spec.method, n_modes=spec.n_modes)
        return res

    def _with_motors(self, system):
        """The lumped linear system with every [[motor]]'s complex stiffness to ground along its coordinate
        (the Maxwell element of (10.65); discrete.motion.motor.with_motor_along)."""
        from discrete.errors import SolverError
        from discrete.motion.motor import with_motor_along

        prob = self.problem_spec().problem()
        if [str(n) for n in prob.names] != [str(n) for n in system.dof_name]:
            raise SolverError("the motor's coordinate and the linear system disagree on the DOFs "
                              f"({list(prob.names)} vs {list(system.dof_name)})")
        for el in prob.elements:
            if el.kind == "motor":
                system = with_motor_along(system, el.g, el.omega0, el.nu, el.T, name=el.name)
        return system

    def _drive_delta(self) -> tuple[float, str]:
        d = self.doc.damping
        kind = "none" if d is None or d.kind == "viscous" else d.kind
        if kind not in ("none", "hysteretic"):
            raise ModelError("[damping]", "type", kind, "'none' | 'hysteretic' for a drive of regular structure")
        if kind == "none":
            return 0.0, "undamped"
        delta = d.psi / (4 * np.pi)
        return delta, f"hysteretic psi = {d.psi:g} (c (1 + 2 i delta), delta = {delta:.6g}) on shaft and mechanism springs"

    def compare(self):
        """Drive files: the three representations, the closed forms and the convergence in n."""
        from .drives import compare_model

        self._drive_delta()
        conv = getattr(self.analysis, "convergence_n", None)
        if conv is not None and self.drive.boundary == "free-free" and min(conv) < 2:
            raise ModelError("[analysis]", "convergence_n", conv, "integers >= 2 for a free-free drive")
        return compare_model(self.drive, convergence_n=conv)

    def simulation_settings(self) -> dict:
        sim = getattr(self.doc, "simulation", None)
        if sim is None:
            raise ModelError(f"model file ({self.kind})", "simulation", None,
                             "a table [simulation] with t_end = .. (required for drivefem simulate)")
        return {"t_end": sim.t_end, "method": sim.method, **sim.options()}

    def simulate(self, progress=None):
        """Time simulation by the method of [simulation] (lumped and hybrid files); ``progress(t)`` is
        called as the integration advances."""
        if self.kind == "rotor":
            return self.run_up(progress)
        settings = self.simulation_settings()
        if progress is not None:
            settings["progress"] = progress
        settings.setdefault("max_evaluations", budget.numeric_evaluations())
        t_end, method = settings["t_end"], settings["method"]
        spp = settings.get("steps_per_period", 12)
        if self.kind == "train":
            from discrete.nonsmooth import simulate_spec

            from .train.simulate import TrainSimulation

            comp = self.compiled_train()
            spec = comp.spec()
            problem = spec.problem() if method != "moreau" else None
            if problem is not None:
                budget.check_time_integration(t_end, problem.omega_max, spp, method)
            if not comp.elements and not comp.forces and not comp.drivers and not np.any(comp.v0) \
                    and not np.any(comp.x0):
                raise ModelError("model file", "force", None, "a [[force]], [[driver]], an initial state or a "
                                 "nonlinear connection (backlash, slip torque, stiffness variation) for a simulation")
            res = simulate_spec(spec, t_end, method, settings, problem=problem)
            return TrainSimulation(result=res, compiled=comp, warnings=list(comp.warnings))
        if self.kind == "hybrid":
            from .hybrid import run

            m = self.hybrid
            if not m.elements and not m.forces and not m.drivers and not m.initial_velocity:
                raise ModelError("model file", "friction", None, "at least one nonsmooth element, [[force]], "
                                 "[[driver]] or [initial] velocity for a simulation")
            self.damping_report = self.compiled.damping_report
            if method != "moreau":
                budget.check_time_integration(t_end, self.compiled.problem.rate_max, spp, method,
                                              self.compiled.problem.nz)
            return run(m, settings, compiled=self.compiled)
        self._need("lumped", what="drivefem simulate")
        from discrete.nonsmooth import simulate_spec

        spec = self.problem_spec(t_end)
        self.damping_report = spec.damping_report
        problem = spec.problem() if method != "moreau" else None
        if problem is not None:
            budget.check_time_integration(t_end, problem.rate_max, spp, method, problem.nz)
        return simulate_spec(spec, t_end, method, settings, problem=problem)

    def run_up(self, progress=None):
        """The run-up of a rotor file ([run_up], [[unbalance]], [[rub]]): :class:`fem.rotor.RunUpResult`;
        ``progress(fraction)`` as it advances."""
        from .rotor import run_up

        self._need("rotor", what="a run-up")
        spec = build_rotor.run_up_spec(self.doc)

        def check_steps(estimate, note):
            budget.check_count("[run_up]", "duration", estimate, budget.MAX_TIME_STEPS, note, spec.run.duration)

        return run_up(self.rotor, spec.run, spec.unbalances, spec.rubs, progress=progress, check_steps=check_steps)

    def steady_model(self):
        """The steady-state model of [steady] (lumped and hybrid files)."""
        from discrete.steady import SteadyModel

        if getattr(self.doc, "steady", None) is None:
            raise ModelError(f"model file ({self.kind})", "steady", None, "a [steady] table")
        spec = self.problem_spec()
        self.damping_report = spec.damping_report
        sm = SteadyModel(spec, steady_settings(self.doc.steady))
        if sm.cfg.method == "hb":
            budget.check_hb(sm.system.n, sm.cfg.harmonics)
            if sm.cfg.adaptive:
                budget.check_hb(sm.system.n, sm.cfg.max_harmonics or 4 * sm.cfg.harmonics, key="max_harmonics")
            if sm.cfg.switch_branches:          # a period-doubled branch has twice the harmonics
                budget.check_hb(sm.system.n, 2 * sm.cfg.harmonics, key="switch_branches")
        if sm.cfg.start == "time":        # the start integrates start_periods response periods (DOP853)
            w0 = float(sm.cfg.range[0])
            t_start = sm.cfg.start_periods * 2 * math.pi * sm.cfg.subharmonic / w0
            budget.check_start_integration(t_start, max(sm.problem0.omega_max, w0), sm.cfg.start_periods)
        return sm


# ------------------------------------------------------------ one-call helpers for model dicts
def simulate(doc: dict):
    """Time simulation of a model given as a dict (as from TOML)."""
    return Study.parse(doc).simulate()


def forced(doc: dict):
    """Forced response (linear, drive, or the nonlinear curve of [steady]) of a model dict."""
    return Study.parse(doc).forced()


def steady_model(doc: dict):
    """The steady-state model of a model dict with a [steady] table."""
    return Study.parse(doc).steady_model()
