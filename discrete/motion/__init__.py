"""Programme motion of drivers and the motor as a model element (textbook §2.5, §5.8-5.10, §6.2, §10.6).

* :mod:`.piecewise`  -- piecewise polynomial (+ sinusoidal) laws, scipy PPoly / CubicSpline interop,
  the exogenous form used by exact integrators;
* :mod:`.cam_laws`   -- standard cam laws and dwell-rise-dwell-return cycles;
* :mod:`.fourier`    -- Fourier series of one period (FFT) with truncation and aliasing errors;
* :mod:`.follower`   -- exact response of a 1-DOF oscillator / elastic follower to a piecewise excitation;
* :mod:`.cam_report` -- Table 6.1, the residual factor (6.8), accumulation factors (5.53), (6.10)-(6.14);
* :mod:`.motor`      -- the dynamic motor characteristic (5.54) as a first-order element.
"""
from .cam_laws import STANDARD_LAWS, characteristic_coefficients, dwell_rise_dwell_return, fall, normalised_rise, rise
from .cam_report import (CamReport, accumulation_factor, admissible_frequency_ratio, band_threshold, cam_report,
                         discontinuity_table, min_frequency_ratio, mu_minus, mu_plus, residual_factor)
from .follower import KnotExcitation, PiecewiseOscillator, SteadyState, particular_solution
from .fourier import FourierSeries, fourier_series
from .piecewise import PiecewiseLaw

__all__ = ["STANDARD_LAWS", "characteristic_coefficients", "dwell_rise_dwell_return", "fall", "normalised_rise", "rise",
           "CamReport", "accumulation_factor", "admissible_frequency_ratio", "band_threshold", "cam_report",
           "discontinuity_table", "min_frequency_ratio", "mu_minus", "mu_plus", "residual_factor", "KnotExcitation",
           "PiecewiseOscillator", "SteadyState", "particular_solution", "FourierSeries", "fourier_series",
           "PiecewiseLaw"]
