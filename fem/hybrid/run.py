"""Running a hybrid model and its result (FE field history, events, energy balance, reduction report)."""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from discrete.nonsmooth.methods import simulate_spec

from ..assembly import FEModel
from .build import CompiledHybrid, HybridModel, compile_hybrid


@dataclass
class HybridResult:
    """Result of a hybrid simulation.

    ``t`` (n_times,) and ``field_history`` (n_times x n_fe_dofs): full FE DOF vectors (constrained
    and driven DOFs included) sampled from the solver's record; ``solver`` the solver's own result
    (:class:`discrete.nonsmooth.SimulationResult` or :class:`discrete.timestepping.SteppingResult`,
    with the history of every solved DOF and, for the event-driven solver, exact event times);
    ``fe`` the FE model; ``compiled`` the problem with its reduction; ``reduction`` the report
    (None for the full model); ``warnings`` solver and reduction warnings.
    """

    t: np.ndarray
    field_history: np.ndarray
    fe: FEModel
    solver: object
    compiled: CompiledHybrid
    reduction: dict | None
    warnings: list[str] = field(default_factory=list)
    method: str = "event"
    wall_time: float = 0.0
    sample_index: np.ndarray | None = None     # the solver's records behind ``t`` (the CSV's named outputs)

    @property
    def events(self):
        return self.solver.events

    @property
    def period(self):
        return self.solver.period

    @property
    def energy_error(self) -> float:
        return float(self.solver.energy_error)

    @property
    def t_end(self) -> float:
        return float(self.solver.t_end)

    def field_at(self, field_name: str, k: int) -> tuple[np.ndarray, np.ndarray]:
        """(x, value) of ``field_name`` at the mesh nodes for sample ``k``."""
        return self.fe.nodal_values(self.field_history[k], field_name)

    def dof_history(self, field_name: str, x: float) -> np.ndarray:
        """History of one FE DOF (by field and position) over the sampled times."""
        j = self.fe.system.dof_index(field=field_name, x=x)
        return self.field_history[:, j]

    def element_force(self, name: str) -> tuple[np.ndarray, np.ndarray]:
        """(t, F) of element ``name`` at the solver's recorded instants: the force along s as the
        solver recorded it (event-driven: the law's force or the constraint force in each recorded
        mode; time stepper: the mean force impulse / dt of each step)."""
        names = [el.name for el in self.compiled.elements]
        if name not in names:
            raise KeyError(f"no element {name!r}; elements: {', '.join(names[:20])}")
        return self.solver.t, self.solver.element_forces[names.index(name)]

    def to_dict(self, events: bool = True) -> dict:
        d = self.solver.to_dict(events=events)
        d.update({"t_end": self.t_end, "period": None if self.period is None else float(self.period),
                  "energy_error": self.energy_error, "integrator": self.method,
                  "reduction": self.reduction, "warnings": list(self.warnings),
                  "n_fe_dofs": int(self.fe.system.n_dofs), "n_solved_dofs": int(self.compiled.system.n_dofs),
                  "n_field_samples": int(self.t.size), "wall_time_s": self.wall_time})
        return d


def _samples(t: np.ndarray, n: int) -> np.ndarray:
    if t.size <= n:
        return np.arange(t.size)
    grid = np.linspace(t[0], t[-1], n)
    idx = np.searchsorted(t, grid).clip(0, t.size - 1)
    return np.unique(idx)


def run(model: HybridModel, settings: dict, compiled: CompiledHybrid | None = None) -> HybridResult:
    """Compile (unless ``compiled`` is given) and integrate ``model`` with the settings of ``[simulation]``."""
    t0 = time.perf_counter()
    comp = compiled or compile_hybrid(model)
    warn = list(comp.warnings)
    method = settings.get("method", "event")
    if method == "moreau" and comp.reduced is not None and settings["dt"] > comp.reduced.suggested_time_step:
        warn.append(f"dt = {settings['dt']:g} s exceeds the reduction's suggested time step "
                    f"{comp.reduced.suggested_time_step:.3g} s (1/20 of the shortest retained period)")
    res = simulate_spec(comp.spec(), settings["t_end"], method, settings,
                        problem=comp.problem if method != "moreau" else None)
    warn += [w for w in res.warnings if w not in warn]
    if res.stopped_early:
        warn.append(f"stopped early: {res.reason}")
    idx = _samples(res.t, settings.get("samples", 2000))
    fld = comp.field(res.x[:, idx])
    return HybridResult(t=res.t[idx], field_history=fld, fe=model.fe, solver=res, compiled=comp,
                        reduction=comp.restitution_report, warnings=warn, method=method,
                        wall_time=time.perf_counter() - t0, sample_index=idx)
