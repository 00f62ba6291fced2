"""All matplotlib figures of the package (files only, Agg backend); each takes a result and draws it."""
from .drives import plot_spectrum_vs_n
from .loads import plot_loads, plot_output_amplitudes
from .extra import (plot_amplitude_curve, plot_campbell, plot_convergence, plot_phase_portrait, plot_solid_vs_beam,
                    plot_time_series)
from .modes import plot_frf, plot_mode_shapes
from .steady import plot_afc
from .time import plot_hybrid, plot_time_history

__all__ = ["plot_spectrum_vs_n", "plot_amplitude_curve", "plot_campbell", "plot_convergence", "plot_phase_portrait",
           "plot_solid_vs_beam", "plot_time_series", "plot_frf", "plot_mode_shapes", "plot_afc", "plot_hybrid",
           "plot_time_history", "plot_loads", "plot_output_amplitudes"]
