"""Writing a finished matplotlib figure to its file (the one way every figure module saves)."""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def save_figure(fig, path, *, dpi: int = 110, tight: bool = True) -> Path:
    """Save ``fig`` to ``path`` (its folder created), laid out tight unless ``tight`` is False (figures that
    placed their axes themselves), and close it; returns the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    if tight:
        fig.tight_layout()
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return path
