"""Parameter sweeps on Dask (``drivefem sweep``).  Entry point: :func:`run_sweep`; see fem/sweep/core.py
for the ``[sweep]`` table and docs/steady.md."""
from .core import apply, collect, evaluate_point, parse_sweep, run_sweep

__all__ = ["run_sweep", "parse_sweep", "evaluate_point", "apply", "collect"]
