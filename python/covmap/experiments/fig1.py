"""The paper's Fig. 1: a cell partly covered by an obstacle.

A wall fills ``x >= x_face`` of a 2 m x 2 m map at 5 cm, with ``x_face`` chosen
so that the wall covers the far ``fraction`` of the target cell (row 20, col
30: x in [1.50, 1.55), y in [1.00, 1.05)). Laser beams from varied positions
and angles hit the face inside the target cell's row. The occupancy grid calls
the cell occupied whatever the fraction; the coverage map recovers the
fraction. :func:`covmap.plot.plot_fig1` draws the runs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from covmap._native import CoverageMap, Grid, LaserModel, OccupancyGrid

if TYPE_CHECKING:
    from collections.abc import Sequence

    import numpy.typing as npt

FRACTIONS = (0.2, 0.5, 0.8)
TARGET = (20, 30)
"""The target cell, ``(row, col)``."""
RESOLUTION_M = 0.05
HALF_ANGLE_RAD = math.radians(20.0)
DISTANCE_RANGE_M = (0.4, 1.2)
RANGE_NOISE_M = 0.005


def grid() -> Grid:
    """The map of the experiment: 2 m x 2 m at 5 cm, origin (0, 0)."""
    return Grid(origin=(0.0, 0.0), resolution=RESOLUTION_M, shape=(40, 40))


@dataclass(frozen=True)
class Run:
    """The outcome of one fraction."""

    fraction: float
    x_face_m: float
    ml: float
    """Maximum-likelihood coverage of the target cell."""
    mean: float
    """Expected coverage of the target cell."""
    occupancy: float
    """Occupancy probability of the target cell."""
    histogram: npt.NDArray[np.float32]
    bin_values: npt.NDArray[np.float64]
    ml_map: npt.NDArray[np.float32]
    observed: npt.NDArray[np.bool_]
    """Cells some reading updated (the rest still hold the uniform prior)."""
    occupancy_map: npt.NDArray[np.float32]

    @property
    def ml_ok(self) -> bool:
        """Whether the ML coverage lies within one bin of the true fraction."""
        step = 1.0 / (len(self.bin_values) - 1)
        return abs(self.ml - self.fraction) <= step + 1e-6

    @property
    def occupancy_ok(self) -> bool:
        """Whether the occupancy grid calls the cell occupied (p > 0.9)."""
        return self.occupancy > 0.9


def run(fraction: float, readings: int, rng: np.random.Generator) -> Run:
    """Integrate ``readings`` laser beams hitting a wall that covers the far
    ``fraction`` of the target cell, into a coverage map and an occupancy grid."""
    g = grid()
    row, col = TARGET
    x_center, y_center = g.cell_center(row, col)
    x_face = x_center + 0.5 * RESOLUTION_M - fraction * RESOLUTION_M
    cmap = CoverageMap(g)
    occupancy = OccupancyGrid(g)
    laser = LaserModel()
    bearing = np.zeros(1)
    for _ in range(readings):
        y_hit = y_center + rng.uniform(-0.02, 0.02)
        phi = rng.uniform(-HALF_ANGLE_RAD, HALF_ANGLE_RAD)
        length = rng.uniform(*DISTANCE_RANGE_M)
        pose = (x_face - length * math.cos(phi), y_hit - length * math.sin(phi), phi)
        ranges = np.array([length + rng.normal(0.0, RANGE_NOISE_M)])
        cmap.integrate(pose, ranges, bearing, laser)
        occupancy.integrate(pose, ranges, bearing, laser)
    ml_map = cmap.ml()
    probabilities = occupancy.probabilities()
    return Run(
        fraction=fraction,
        x_face_m=x_face,
        ml=float(ml_map[row, col]),
        mean=float(cmap.mean()[row, col]),
        occupancy=float(probabilities[row, col]),
        histogram=cmap.histogram(row, col),
        bin_values=cmap.bin_values,
        ml_map=ml_map,
        observed=cmap.entropy() < math.log(cmap.bins) - 1e-4,
        occupancy_map=probabilities,
    )


def run_all(seed: int, readings: int, fractions: Sequence[float] = FRACTIONS) -> list[Run]:
    """One run per fraction, each with its own random stream spawned from ``seed``
    (so a fraction's result does not depend on which others ran before it)."""
    streams = np.random.SeedSequence(seed).spawn(len(fractions))
    return [run(f, readings, np.random.default_rng(s)) for f, s in zip(fractions, streams)]


def table(runs: Sequence[Run]) -> str:
    """The results as a fixed-width text table."""
    lines = [
        f"{'fraction':>8}  {'ML':>6}  {'mean':>6}  {'p(occ)':>6}  {'ML within 1 bin':>15}  {'p(occ) > 0.9':>12}",
    ]
    for r in runs:
        lines.append(
            f"{r.fraction:>8.2f}  {r.ml:>6.3f}  {r.mean:>6.3f}  {r.occupancy:>6.3f}  "
            f"{'yes' if r.ml_ok else 'NO':>15}  {'yes' if r.occupancy_ok else 'NO':>12}"
        )
    return "\n".join(lines)
