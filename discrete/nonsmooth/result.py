"""Result of a nonsmooth simulation: time history, events, period, energy balance."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass
class Event:
    t: float
    kind: str            # stick | slip | reversal | impact | contact_open | contact_close
    element: str
    state: dict          # {dof name: {"x": .., "v": ..}}

    def to_dict(self) -> dict:
        return {"t": float(self.t), "kind": self.kind, "element": self.element,
                "state": {k: {"x": float(s["x"]), "v": float(s["v"])} for k, s in self.state.items()}}


@dataclass
class SimulationResult:
    """Time history (``t``; ``x``, ``v`` with one row per DOF named in ``names``), events,
    detected period, and energy balance ``energy`` (E(t)) vs ``work`` (integrated
    non-conservative power plus impact losses) at the same instants."""

    t: np.ndarray
    x: np.ndarray
    v: np.ndarray
    names: list[str]
    events: list[Event]
    t_end: float
    energy: np.ndarray
    work: np.ndarray
    energy_error: float
    period: float | None = None
    period_info: dict = field(default_factory=dict)
    n_pieces: int = 0
    n_steps: int = 0
    step_rejections: int = 0
    warnings: list[str] = field(default_factory=list)
    stopped_early: bool = False
    reason: str = ""
    method: str = "event-driven"
    elements: list[str] = field(default_factory=list)
    driven: list[str] = field(default_factory=list)     # DOFs with prescribed motion (drivers)
    work_parts: dict = field(default_factory=dict)      # total work by source (drivers, friction, impacts, ...)

    def events_of(self, kind: str | None = None, element: str | None = None) -> list[Event]:
        return [e for e in self.events if (kind is None or e.kind == kind) and (element is None or e.element == element)]

    def event_times(self, kind: str | None = None, element: str | None = None) -> np.ndarray:
        return np.array([e.t for e in self.events_of(kind, element)])

    def series(self, name: str) -> tuple[np.ndarray, np.ndarray]:
        i = self.names.index(name)
        return self.x[i], self.v[i]

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
            "period_info": self.period_info,
            "energy_error": float(self.energy_error),
            "energy_final": float(self.energy[-1]) if self.energy.size else None,
            "work_final": float(self.work[-1]) if self.work.size else None,
            "work_parts": {k: float(v) for k, v in self.work_parts.items()},
            "n_pieces": self.n_pieces,
            "n_steps": self.n_steps,
            "step_rejections": self.step_rejections,
            "warnings": list(self.warnings),
            "stopped_early": bool(self.stopped_early),
            "reason": self.reason,
            "dofs": list(self.names),
            "driven_dofs": list(self.driven),
            "elements": list(self.elements),
        }
