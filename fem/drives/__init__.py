"""Drives of regular structure (textbook ch. 10): a main shaft with n identical mechanisms,
solvable three ways -- the discrete FE/lumped model, transfer matrices with the closed-form
spectra of regular structures, and the continuum pseudo-medium (two-field scikit-fem).

Entry points: :func:`modal`, :func:`forced`, :func:`compare_model` on a :class:`DriveModel`;
model files (``[drive]``) go through :mod:`fem.modelfile` and :class:`fem.study.Study`.
See docs/drives.md for the ``[drive]`` keys.
"""
from .analysis import (DriveComparison, DriveForcedResult, DriveModalResult, compare_model, forced, modal,
                       spectrum_sweep)
from .model import DistributedShaft, DriveModel, LumpedShaft, Mechanism

__all__ = ["modal", "forced", "compare_model", "spectrum_sweep", "DriveModel", "LumpedShaft", "DistributedShaft",
           "Mechanism", "DriveModalResult", "DriveForcedResult", "DriveComparison"]
