"""Section loads along FE shafts, rods, beams and rotors: :func:`section_loads`, :func:`rotor_section_loads`.

Sign convention (docs/loads.md): the section load at x is the force and moment that the material on
the +x side exerts on the material on the -x side (the resultant on the face whose outward normal is
+x).  Torque and bending moments are moment vectors (right-hand rule); forces are along the axes.
Plane beams ([[segment]] bending, DOFs w and its slope or rotation) lie in the x-y plane of that
convention: ``shear_force`` is along +w, ``bending_moment`` is conjugate to the slope (M = E I w'' for
Euler-Bernoulli, E I phi' for Timoshenko), so that away from loads and inertia dM/dx = -V.
"""
from __future__ import annotations

import math
import weakref
from dataclasses import dataclass, field

import numpy as np

from discrete.errors import ModelError

from .elements import ElementSet
from .motion import WHERE, ElementDamping, Motion, motion
from .recovery import element_end_stations, end_forces, station_values

UNITS = {"torque": "N m", "axial_force": "N", "bending_moment": "N m", "shear_force": "N",
         "bending_moment_y": "N m", "bending_moment_z": "N m", "shear_force_y": "N", "shear_force_z": "N"}
SIDES = ("right", "left")


@dataclass
class SectionLoads:
    """Section loads at the stations ``x`` (m).

    ``quantities[name]`` is (n_x,) for one state or (n_x, n_t) for several (time samples,
    frequencies, modes), complex for harmonic amplitudes and modes; ``units[name]`` is "N m" or "N".
    ``side[i]`` says on which side of x_i the value holds: "right" (just right of x: taken from the
    element that starts there) or "left" (just left of x); at a node with a point load, point
    inertia, spring or support the two differ by exactly that nodal force.  ``element`` is the
    element each value comes from, ``kind`` static | harmonic | modal | time, ``parameter`` the
    angular frequency (harmonic, rad/s) or eigenvalue (modal, 1/s) of every column, ``notes`` what
    the values do not contain."""

    x: np.ndarray
    quantities: dict
    units: dict
    side: np.ndarray
    element: np.ndarray
    kind: str
    parameter: np.ndarray | None = None
    notes: list = field(default_factory=list)

    def __getitem__(self, name: str) -> np.ndarray:
        return self.quantities[name]

    def to_dict(self) -> dict:
        d = {"x": self.x, "side": [str(s) for s in self.side], "kind": self.kind,
             "quantities": list(self.quantities), "units": dict(self.units),
             "values": {k: v for k, v in self.quantities.items()}, "notes": list(self.notes)}
        if self.parameter is not None:
            key = "omega_rad_s" if self.kind == "harmonic" else "eigenvalues"
            d[key] = self.parameter
        return d


# ------------------------------------------------------------------ element sets, built once per model
_CACHE: dict[int, tuple] = {}


def elements_of(model) -> ElementSet:
    """The :class:`ElementSet` of an assembled FE model or rotor (built once per object)."""
    key = id(model)
    hit = _CACHE.get(key)
    if hit is not None and hit[0]() is model:
        return hit[1]
    from ..assembly import FEModel
    from ..rotor.assembly import RotorSystem

    if isinstance(model, FEModel):
        from .shaft_elements import shaft_elements

        es = shaft_elements(model)
    elif isinstance(model, RotorSystem):
        from .rotor_elements import rotor_elements

        es = rotor_elements(model)
    else:
        raise ModelError(WHERE, "model", type(model).__name__, "an assembled fem.FEModel (fem.assemble) or "
                         "fem.rotor.RotorSystem (fem.rotor.assemble_rotor)")
    _CACHE[key] = (weakref.ref(model, lambda _r, k=key: _CACHE.pop(k, None)), es)
    return es


def _stations(es: ElementSet, x, side: str):
    if side not in SIDES:
        raise ModelError(WHERE, "side", side, " | ".join(map(repr, SIDES)))
    if x is None:
        return element_end_stations(es)
    try:
        xs = np.atleast_1d(np.asarray(x, dtype=float))
    except (TypeError, ValueError):
        xs = np.zeros((0,))
    if xs.ndim != 1 or xs.size == 0:
        raise ModelError(WHERE, "x", x, "a station or a list of stations along the shaft (m)")
    located = [es.locate(float(v), side) for v in xs]
    return (np.array([e for e, _ in located]), np.array([t for _, t in located]),
            np.array([side if 0 < t < 1 else ("right" if t == 0 else "left") for _, t in located], dtype=object))


def _result(es: ElementSet, mo: Motion, damping: ElementDamping, stations, *, speed=0.0, load=None,
            notes=()) -> SectionLoads:
    element, xi, side = stations
    used, rows = np.unique(element, return_inverse=True)
    f = end_forces(es, mo, damping, speed=speed, load=load, elements=used)
    vals = station_values(es, f, mo, damping, element, xi, side, speed=speed, load=load, rows=rows)
    x = es.x0[element] + xi * es.length[element]
    if mo.single:
        vals = {k: v[:, 0] for k, v in vals.items()}
    notes = list(notes) + ([damping.note] if damping.note else [])
    return SectionLoads(x=x, quantities=vals, units={k: UNITS[k] for k in vals}, side=side, element=element,
                        kind=mo.kind, parameter=None if mo.parameter is None else
                        (mo.parameter[0] if mo.single else mo.parameter), notes=notes)


def section_loads(fe_model, q, *, qd=None, qdd=None, omega=None, x=None, eigenvalue=None, damping=None,
                  side: str = "right", speed=None, gravity=None) -> SectionLoads:
    """Section loads of an assembled model (what :func:`fem.assemble` returns, or a rotor's
    :class:`~fem.rotor.RotorSystem`, see :func:`rotor_section_loads`) for the DOF vector(s) ``q``.

    ``q``: (n_dofs,) or (n_dofs, n_t), real or complex, every DOF of the model (constrained ones
    included).  Static: ``q`` only; harmonic: complex amplitudes at ``omega`` (rad/s, one or one per
    column; with the loss stiffness i H of segment psi and ``damping``, a
    :class:`discrete.linear.Damping` as given to the harmonic analysis); a mode: its shape at
    ``eigenvalue`` (lambda = i omega_n for an undamped mode); time history: ``qd``, ``qdd`` as well.
    ``x``: stations (m); None: both ends of every element (x repeats at inner nodes).  At a node,
    ``side`` picks the element right ("right") or left ("left") of x.  Rotors: ``speed`` (rad/s) for
    the gyroscopic moments, ``gravity`` (g_x, g_y, g_z) for static deflections under self-weight.
    """
    from ..rotor.assembly import RotorSystem

    if isinstance(fe_model, RotorSystem):
        if damping is not None:
            raise ModelError(WHERE, "damping", damping, "None for a rotor (its damping is in its bearings, seals and "
                             "couplings)")
        return rotor_section_loads(fe_model, q, qd=qd, qdd=qdd, omega=omega, x=x, eigenvalue=eigenvalue,
                                   side=side, speed=speed, gravity=gravity)
    for key, value in (("speed", speed), ("gravity", gravity)):
        if value is not None:
            raise ModelError(WHERE, key, value, "only for rotors (a fem.rotor.RotorSystem)")
    es = elements_of(fe_model)
    mo = motion(es.n_dofs, q, qd, qdd, omega, eigenvalue)
    return _result(es, mo, ElementDamping.of(damping), _stations(es, x, side))


def rotor_section_loads(rotor_system, q, *, qd=None, qdd=None, omega=None, x=None, eigenvalue=None,
                        speed: float | None = None, gravity=None, side: str = "right") -> SectionLoads:
    """Section loads of a rotor (:class:`~fem.rotor.RotorSystem`): bending moments M_y, M_z, shear
    forces V_y, V_z, and with ``dofs = "full"`` torque and axial force.  ``speed`` (rad/s): the spin
    speed of the gyroscopic moments (default: ``omega`` -- the synchronous unbalance response --, else 0);
    ``gravity`` (g_x, g_y, g_z, m/s^2): the weight of the shaft as distributed load (static deflection).
    The rest as :func:`section_loads`."""
    from ..rotor.assembly import RotorSystem

    if not isinstance(rotor_system, RotorSystem):
        raise ModelError(WHERE, "rotor_system", type(rotor_system).__name__, "a fem.rotor.RotorSystem")
    es = elements_of(rotor_system)
    mo = motion(es.n_dofs, q, qd, qdd, omega, eigenvalue)
    if speed is None:
        speed = mo.parameter.real if mo.kind == "harmonic" else 0.0
    try:
        spin = np.broadcast_to(np.asarray(speed, dtype=float), (mo.q.shape[1],))
    except (TypeError, ValueError):
        spin = None
    if spin is None or not np.all(np.isfinite(spin)) or np.any(spin < 0):
        raise ModelError(WHERE, "speed", speed, "a spin speed >= 0 (rad/s), one or one per column of q")
    load = None if gravity is None else _gravity(gravity)
    return _result(es, mo, ElementDamping(), _stations(es, x, side), speed=spin, load=load)


def _gravity(g) -> np.ndarray:
    try:
        arr = np.asarray(g, dtype=float).ravel()
    except (TypeError, ValueError):
        arr = np.zeros(0)
    if arr.shape != (3,) or not np.all(np.isfinite(arr)):
        raise ModelError(WHERE, "gravity", g, "three finite numbers (g_x, g_y, g_z), m/s^2")
    return arr
