"""Errors raised on bad input: each names the key, its value and what is allowed."""


class ModelError(ValueError):
    """Bad model input.  The message names the offending key, its value and what is allowed."""

    def __init__(self, where: str, key: str, value, allowed: str):
        self.where, self.key, self.value, self.allowed = where, key, value, allowed
        loc = f"{where}: " if where else ""
        super().__init__(f"{loc}{key} = {value!r} is not valid; allowed: {allowed}")


class SolverError(RuntimeError):
    """A solver could not produce a trustworthy result (singular system, no convergence)."""
