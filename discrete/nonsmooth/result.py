"""Results of nonsmooth simulations: time history, events, period, energy balance.

:class:`TimeHistory` holds what every solver records; :class:`SimulationResult` (event-driven and
regularised) and :class:`discrete.timestepping.SteppingResult` (Moreau-Jean) add their own statistics."""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import KW_ONLY, dataclass, field

import numpy as np


class EventState(Mapping):
    """The DOF states ``{name: {"x": .., "v": ..}}`` of one event, read from the run's arrays of
    event states (one column per event) when first looked at: a run with thousands of events
    builds no dictionaries nobody reads."""

    __slots__ = ("_names", "_x", "_v", "_k", "_d")

    def __init__(self, names, x: np.ndarray, v: np.ndarray, k: int):
        self._names, self._x, self._v, self._k, self._d = names, x, v, k, None

    def _dict(self) -> dict:
        if self._d is None:
            k = self._k
            self._d = {n: {"x": float(xk), "v": float(vk)} for n, xk, vk in zip(self._names, self._x[:, k], self._v[:, k])}
        return self._d

    def __getitem__(self, name):
        return self._dict()[name]

    def __iter__(self):
        return iter(self._names)

    def __len__(self) -> int:
        return len(self._names)

    def __repr__(self) -> str:
        return repr(self._dict())

    def __reduce__(self):
        return dict, (self._dict(),)


def state_velocities(states, names) -> np.ndarray:
    """(n_states, n_names) velocities ``state[name]["v"]`` of event states: read straight from the
    run's array when they are :class:`EventState` views of one run (no dictionaries built)."""
    first = states[0] if states else None
    if type(first) is EventState and all(type(s) is EventState and s._v is first._v and s._names is first._names
                                         for s in states):
        rows = [first._names.index(k) for k in names]
        return first._v[np.ix_(rows, [s._k for s in states])].T.astype(float)
    return np.array([[s[k]["v"] for k in names] for s in states], dtype=float)


@dataclass
class Event:
    t: float
    kind: str            # stick | slip | reversal | impact | contact_open | contact_close
    element: str
    state: Mapping       # {dof name: {"x": .., "v": ..}} (an EventState or a dict)
    impulse: float = 0.0  # generalised impulse along s the element's event rule applied (an impact's
    #                       momentum jump m_eff (s'+ - s'-); 0 where the rule moved no velocity)

    def to_dict(self) -> dict:
        return {"t": float(self.t), "kind": self.kind, "element": self.element,
                "state": {k: {"x": float(s["x"]), "v": float(s["v"])} for k, s in self.state.items()}}


@dataclass
class TimeHistory:
    """Time history (``t``; ``x``, ``v`` with one row per DOF named in ``names``, drivers included),
    events, detected period, and energy balance ``energy`` (E(t)) vs ``work`` (integrated
    non-conservative power plus impact losses) at the same instants.  The fields after
    ``energy_error`` are keyword-only; subclasses add theirs to :meth:`to_dict` by the two hooks."""

    t: np.ndarray
    x: np.ndarray
    v: np.ndarray
    names: list[str]
    events: list[Event]
    t_end: float
    energy: np.ndarray
    work: np.ndarray
    energy_error: float
    _: KW_ONLY
    method: str
    period: float | None = None
    warnings: list[str] = field(default_factory=list)
    stopped_early: bool = False
    reason: str = ""
    elements: list[str] = field(default_factory=list)
    driven: list[str] = field(default_factory=list)     # DOFs with prescribed motion (drivers)
    element_forces: np.ndarray | None = None            # (n_elements, n_times): force along s of every
    #                                                     element at the recorded instants (None: not recorded)
    acceleration: np.ndarray | None = None              # (n_dofs, n_times) accelerations of every DOF (drivers:
    #                                                     their law) from the equations of motion (None: not recorded)
    applied: np.ndarray | None = None                   # (n_forces, n_times) value of every external force

    def events_of(self, kind: str | None = None, element: str | None = None) -> list[Event]:
        return [e for e in self.events if (kind is None or e.kind == kind) and (element is None or e.element == element)]

    def event_times(self, kind: str | None = None, element: str | None = None) -> np.ndarray:
        return np.array([e.t for e in self.events_of(kind, element)])

    def series(self, name: str) -> tuple[np.ndarray, np.ndarray]:
        i = self.names.index(name)
        return self.x[i], self.v[i]

    def _period_dict(self) -> dict:
        """Keys following ``period`` in :meth:`to_dict`."""
        return {}

    def _solver_dict(self) -> dict:
        """Keys following the energy balance in :meth:`to_dict` (work by source, solver statistics)."""
        return {}

    def to_dict(self, events: bool = True) -> dict:
        counts: dict[str, int] = {}
        for e in self.events:
            counts[e.kind] = counts.get(e.kind, 0) + 1
        return {
            "method": self.method,
            "t_end": float(self.t_end),
            "t_reached": float(self.t[-1]) if self.t.size else 0.0,
            "events": [e.to_dict() for e in self.events] if events else [],
            "n_events": len(self.events),
            "event_counts": counts,
            "period": None if self.period is None else float(self.period),
            **self._period_dict(),
            "energy_error": float(self.energy_error) if np.isfinite(self.energy_error) else None,  # strict JSON
            "energy_final": float(self.energy[-1]) if self.energy.size else None,
            "work_final": float(self.work[-1]) if self.work.size else None,
            **self._solver_dict(),
            "warnings": list(self.warnings),
            "stopped_early": bool(self.stopped_early),
            "reason": self.reason,
            "dofs": list(self.names),
            "driven_dofs": list(self.driven),
            "elements": list(self.elements),
        }


@dataclass
class SimulationResult(TimeHistory):
    """Result of the event-driven (or regularised) solver: :class:`TimeHistory` plus the period
    detection details, the total work by source and the integration statistics."""

    period_info: dict = field(default_factory=dict)
    n_pieces: int = 0
    n_steps: int = 0
    step_rejections: int = 0
    work_parts: dict = field(default_factory=dict)      # total work by source (drivers, friction, impacts, ...)
    method: str = field(default="event-driven", kw_only=True)

    def _period_dict(self) -> dict:
        return {"period_info": self.period_info}

    def _solver_dict(self) -> dict:
        return {"work_parts": {k: float(v) for k, v in self.work_parts.items()}, "n_pieces": self.n_pieces,
                "n_steps": self.n_steps, "step_rejections": self.step_rejections}
