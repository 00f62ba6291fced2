"""Rotordynamics: spinning Timoshenko shafts with discs, bearings and seals, pedestals and couplings.

Build a :class:`Rotor` (the description), assemble it (:func:`assemble_rotor`, or let each
analysis do it), and run the analyses:

* :func:`rotor_modes` -- complex modes at a speed (damped frequencies, log decrement, whirl, orbits);
* :func:`campbell` / :func:`critical_speeds` -- tracked modes over a speed range, critical speeds
  as roots of omega(Omega) = k Omega;
* :func:`undamped_critical_speeds`, :func:`critical_speed_map` -- the undamped critical speeds
  from a linear eigenproblem, and their map against bearing stiffness;
* :func:`unbalance_response` -- Bode/polar data, orbits, peaks with AF and separation margins;
* :func:`static_deflection` -- deflection under gravity and point loads, bearing loads;
* :func:`stability_threshold` -- the onset speed of instability (cross-coupled stiffness);
* :func:`api_level1` -- the API 617 / API RP 684 Level I stability screening (Wachel's Q_A);
* :func:`synchronous_response` -- the 1x (tracking filter) response of a run-up: its Bode plot;
* :func:`run_up` -- a run-up through the speed range with rotor-stator rubs and bearing
  clearances (:class:`Rub`), compliant contacts located event by event or rigid ones by
  Moreau-Jean, on a reduced rotor that reports its restitution, with the energy balance;
* bearings computed from their geometry (:mod:`fem.rotor.bearings`, imported on first use):
  :class:`JournalBearing` (Reynolds film), :class:`RollingBearing`, :class:`SqueezeFilmDamper`,
  with their nonlinear laws in run-ups, and :func:`whirl_onset` / :func:`cascade` of a run-up.

Figures are in :mod:`fem.rotor.plots`, 3D whirl pictures in :mod:`fem.rotor.render`.
``RotorSystem.system_at(speed)`` gives the :class:`~discrete.linear_system.LinearSystem`
M q'' + (C + Omega G) q' + K q = f at a speed and ``RotorSystem.dof(x, field)`` the DOF at a
position, for elements that act on the rotor.
"""
from .api_level1 import LevelIResult, Stage, anticipated_cross_coupling, api_level1
from .assembly import RotorSystem, assemble_rotor
from .campbell import CampbellResult, CriticalSpeed, campbell, critical_speeds
from .critical_map import CriticalSpeedMap, UndampedCriticalSpeeds, critical_speed_map, undamped_critical_speeds
from .modal import RotorModes, rotor_modes
from .model import Bearing, Coupling, Disc, Layer, Pedestal, Rotor, ShaftSegment, Support, Unbalance, rpm, to_rpm
from .runup import Rub, RunUp, RunUpResult, run_up
from .runup_tracking import SynchronousResponse, synchronous_response
from .response import Probe, UnbalanceResponse, required_margin, unbalance_response
from .stability import StabilityResult, stability_threshold
from .static import PointLoad, StaticResult, static_deflection
from .whirl import Orbits, mac

from discrete.lazy import lazy_exports as _lazy_exports   # noqa: E402

# bearings computed from their geometry load scikit-fem: on first use only
_LAZY = {"JournalBearing": "fem.rotor.bearings.journal", "RollingBearing": "fem.rotor.bearings.rolling",
         "SqueezeFilmDamper": "fem.rotor.bearings.squeeze_film", "whirl_onset": "fem.rotor.whirl_spectrum",
         "cascade": "fem.rotor.whirl_spectrum"}
__getattr__, __dir__ = _lazy_exports(__name__, _LAZY, globals())

__all__ = ["Rotor", "ShaftSegment", "Layer", "Disc", "Bearing", "Pedestal", "Coupling", "Support", "Unbalance", "rpm", "to_rpm",
           "RotorSystem", "assemble_rotor", "RotorModes", "rotor_modes", "CampbellResult", "CriticalSpeed", "campbell",
           "critical_speeds", "UndampedCriticalSpeeds", "undamped_critical_speeds", "CriticalSpeedMap",
           "critical_speed_map", "Probe", "UnbalanceResponse", "unbalance_response", "required_margin",
           "PointLoad", "StaticResult", "static_deflection", "StabilityResult", "stability_threshold", "Orbits", "mac",
           "Rub", "RunUp", "RunUpResult", "run_up", "Stage", "LevelIResult", "api_level1", "anticipated_cross_coupling",
           "SynchronousResponse", "synchronous_response", *_LAZY]
