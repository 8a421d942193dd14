"""Writing a figure: the one place for the PNG settings of every plot of the project."""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

if TYPE_CHECKING:
    from matplotlib.figure import Figure


def savefig(fig: Figure, path: str | Path, dpi: int = 150) -> Path:
    """Save ``fig`` as PNG (parent directories created) and close it.

    A figure made with a layout engine (``layout="constrained"``) is already fitted to its
    labels and is drawn once; one without gets a tight bounding box (an extra draw).
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tight = fig.get_layout_engine() is None
    fig.savefig(path, dpi=dpi, bbox_inches="tight" if tight else None)
    plt.close(fig)
    return path
