"""Figures written to PNG files whole or not at all."""

from __future__ import annotations

import io
from pathlib import Path
from typing import TYPE_CHECKING

from covmap._native import write_atomic

if TYPE_CHECKING:
    import os

    from matplotlib.figure import Figure


def save_figure(fig: Figure, path: str | os.PathLike[str], *, dpi: int = 100) -> Path:
    """Write ``fig`` to ``path`` as PNG atomically (rendered in memory, then
    written to a temporary file in the same directory and renamed, so a
    reader never sees a partial file), creating the directory; the PNG
    carries no software or date stamp, so the same figure gives the same
    bytes. Returns the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    png = io.BytesIO()
    fig.savefig(png, format="png", dpi=dpi, metadata={"Software": None})
    # The simulator's writer, the one its GeoJSON files and pictures go through.
    write_atomic(path, png.getvalue())
    return path
