"""The paper's Fig. 2: the inverse sensor model ``p(c_l = x | d)`` over the
cell distance ``d_l`` and the coverage ``x``, for one measured distance."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from covmap.plot.figures import _figure_file

if TYPE_CHECKING:
    from collections.abc import Sequence
    from pathlib import Path

    from covmap._native import LaserModel, SonarModel


def model_grid(
    model: SonarModel | LaserModel, distance: float, *, resolution: float = 0.05, bins: int = 16
) -> tuple[np.ndarray, np.ndarray]:
    """The kernels of ``model`` for a reading of ``distance`` metres at cell
    distances from 0 to the reading's reach (steps of a fifth of a cell):
    the distances, and an array ``(bins, len(distances))`` of ``p(x | d)``
    (NaN where the cell is not updated)."""
    reach = distance + model.band_m + resolution
    d_l = np.arange(0.0, reach, resolution / 5)
    columns = []
    for x in d_l:
        k = model.kernel(float(x), distance, resolution=resolution, bins=bins)
        columns.append(np.full(bins, np.nan) if k is None else k.astype(np.float64))
    return d_l, np.stack(columns, axis=1)


def plot_fig2(
    models: Sequence[tuple[str, SonarModel | LaserModel]],
    distance: float,
    path: Path,
    *,
    resolution: float = 0.05,
    bins: int = 16,
) -> Path:
    """Fig. 2 for each ``(title, model)`` side by side: ``p(c_l = x | d)`` as
    an image over ``d_l`` (x axis) and ``x`` (y axis), for the measured
    distance ``distance``; written to ``path`` as PNG."""
    with _figure_file(path, 1, len(models), figsize=(5.5 * len(models), 4.2), squeeze=False) as (
        fig,
        axes,
    ):
        for ax, (title, model) in zip(axes[0], models, strict=True):
            d_l, p = model_grid(model, distance, resolution=resolution, bins=bins)
            image = ax.imshow(
                np.ma.masked_invalid(p),
                origin="lower",
                aspect="auto",
                extent=(d_l[0], d_l[-1], -0.5 / (bins - 1), 1 + 0.5 / (bins - 1)),
                cmap="viridis",
            )
            ax.axvline(distance, color="white", lw=0.8, ls="--")
            ax.set_xlabel("cell distance $d_l$ (m)")
            ax.set_ylabel("coverage $x$")
            ax.set_title(f"{title}: $p(c_l = x \\mid d = {distance:g}$ m$)$")
            fig.colorbar(image, ax=ax, label="probability")
        fig.tight_layout()
    return path
