"""The shipped example model files, as the validation cases load them (each case runs its example's
model, overriding only what it sweeps)."""
from __future__ import annotations

from pathlib import Path

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def example_doc(name: str) -> dict:
    """The model dict of ``examples/<name>`` (read and checked as the CLI reads it)."""
    from fem.modelfile.source import read_toml

    return read_toml(EXAMPLES / name)
