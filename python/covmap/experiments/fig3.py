"""The paper's Fig. 3: a coverage map of a corridor built from ultrasound.

:func:`covmap.run_fig3` drives 24 simulated sonars along a seeded path through
the built-in ``corridor`` and measures the coverage map and an occupancy grid
fed by the same readings against the exact ground truth; it returns a
:class:`Fig3Result`. This module prints its figures;
:func:`covmap.plot.plot_fig3` draws its maps.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any


if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt

    from covmap._native import Grid


class _Indexable:
    """``result["name"]`` for ``result.name``: the results were dicts once."""

    def __getitem__(self, key: str) -> Any:
        if key not in getattr(self, "__dataclass_fields__"):
            raise KeyError(key)
        return getattr(self, key)


@dataclass(frozen=True)
class MapErrors(_Indexable):
    """Mean absolute errors of one estimated map against the ground truth."""

    all: float
    """Over every cell a reading reached."""
    partial: float
    """Over the reached cells a wall face cuts (partly covered)."""


@dataclass(frozen=True)
class Fig3Result(_Indexable):
    """What :func:`covmap.run_fig3` measured. Per-cell maps are ``(rows, cols)``."""

    grid: Grid
    poses: npt.NDArray[np.float64]
    """The path, ``(x, y, theta)`` a row."""
    readings: int
    """Sonar readings integrated."""
    cells_reached: int
    """Cells some reading reached."""
    truth: npt.NDArray[np.float64]
    """Exact coverage of every cell."""
    ml: npt.NDArray[np.float32]
    """The coverage map's maximum-likelihood coverage."""
    mean: npt.NDArray[np.float32]
    """The coverage map's mean coverage."""
    entropy: npt.NDArray[np.float32]
    """The coverage map's entropy, nats."""
    occupancy: npt.NDArray[np.float32]
    """The occupancy grid's probabilities."""
    reached: npt.NDArray[np.bool_]
    """Whether some reading reached each cell."""
    mae_ml: MapErrors
    """Errors of the maximum-likelihood map."""
    mae_mean: MapErrors
    """Errors of the mean map."""
    mae_occupancy: MapErrors
    """Errors of the occupancy probabilities read as coverage."""
    log_likelihood: float
    """Log-likelihood of the truth under the coverage map."""
    log_likelihood_prior: float
    """The same under the uniform prior, for scale."""


def table(result: Fig3Result, seed: int) -> str:
    """The figures of a :func:`covmap.run_fig3` result as text."""
    lines = [
        f"Fig. 3, corridor, 24 sonars, seed {seed}: {len(result.poses)} poses, "
        f"{result.readings} readings, {result.cells_reached} cells reached",
        f"{'mean absolute error':<22}  {'all reached':>11}  {'partly covered':>14}",
    ]
    for errors, name in (
        (result.mae_ml, "coverage map, ML"),
        (result.mae_mean, "coverage map, mean"),
        (result.mae_occupancy, "occupancy grid"),
    ):
        lines.append(f"{name:<22}  {errors.all:>11.4f}  {errors.partial:>14.4f}")
    lines.append(
        f"log-likelihood of the truth: {result.log_likelihood:.1f} "
        f"(uniform prior: {result.log_likelihood_prior:.1f})"
    )
    return "\n".join(lines)
