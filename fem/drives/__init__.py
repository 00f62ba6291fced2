"""Drives of regular structure (textbook ch. 10): a main shaft with n identical mechanisms,
solvable three ways -- the discrete FE/lumped model, transfer matrices with the closed-form
spectra of regular structures, and the continuum pseudo-medium (two-field scikit-fem).

Entry points for the CLI: :data:`TOP_LEVEL_KEYS`, :func:`is_drive`, :func:`drive_modal`,
:func:`drive_forced`, :func:`compare`.  See docs/drives.md for the ``[drive]`` keys.
"""
from __future__ import annotations

#: top-level model-file keys of a drive model (anything else is an error)
TOP_LEVEL_KEYS = ("drive", "title", "analysis", "damping")


def is_drive(doc: dict) -> bool:
    """True when the parsed model file describes a drive (has a ``[drive]`` table)."""
    return isinstance(doc, dict) and "drive" in doc


from .analysis import (DriveComparison, DriveForcedResult, DriveModalResult, compare, compare_model,  # noqa: E402
                       drive_forced, drive_modal, forced, modal)
from .model import DistributedShaft, DriveModel, LumpedShaft, Mechanism, parse_drive  # noqa: E402

__all__ = ["TOP_LEVEL_KEYS", "is_drive", "drive_modal", "drive_forced", "compare", "compare_model", "modal",
           "forced", "DriveModel", "LumpedShaft", "DistributedShaft", "Mechanism", "parse_drive",
           "DriveModalResult", "DriveForcedResult", "DriveComparison"]
