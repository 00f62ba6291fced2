"""Old spellings and implicit defaults of model files that still work, with a warning naming the new key."""
from __future__ import annotations

import warnings


class ModelDeprecationWarning(UserWarning):
    """An old spelling or an implicit default of a model file that still works, naming the new key."""


def warn_deprecated(where: str, message: str) -> None:
    warnings.warn(f"{where}: {message}", ModelDeprecationWarning, stacklevel=3)
