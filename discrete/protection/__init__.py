"""Vibration protection (textbook ch. 6): transmissibility, loads proportional to omega^2, isolation
inequalities, the dynamic absorber, dynamic unloading and the quasi-constant platform.

Element forces and support/driver reactions of any harmonic response are in
:mod:`discrete.linear.reactions`.
"""
from .absorber import Absorber, tuned_stiffness
from .isolation import IsolationDesign, MovingMassIsolation, damped_stiffness_limit, isolation_design
from .quasi_constant import QuasiConstantPlatform, kappa, kappa_extrema
from .transmissibility import dynamic_factor, force_transmissibility, relative_motion_factor
from .unbalance import unbalance_response, unbalance_spectrum
from .unloading import UnloadingSpring, harmonic_unloading, unloading_spring

__all__ = ["Absorber", "tuned_stiffness", "IsolationDesign", "MovingMassIsolation", "damped_stiffness_limit",
           "isolation_design", "QuasiConstantPlatform", "kappa", "kappa_extrema", "dynamic_factor",
           "force_transmissibility", "relative_motion_factor", "unbalance_response", "unbalance_spectrum",
           "UnloadingSpring", "harmonic_unloading", "unloading_spring"]
