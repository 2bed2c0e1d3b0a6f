"""Coverage maps for mobile robots (Stachniss and Burgard, 2003).

Every cell of a :class:`CoverageMap` holds a histogram over how much of the
cell is covered by obstacles, updated by Bayes' rule with the inverse sensor
model of a sonar cone (:class:`SonarModel`) or a laser beam
(:class:`LaserModel`). :class:`OccupancyGrid` is the classic baseline fed by
the same beams.

>>> import numpy as np, covmap
>>> grid = covmap.Grid(origin=(0.0, 0.0), resolution=0.05, shape=(40, 40))
>>> cmap = covmap.CoverageMap(grid)
>>> laser = covmap.LaserModel()
>>> updates = cmap.integrate((0.5, 1.025, 0.0), np.array([1.0]), np.array([0.0]), laser)
>>> grid.world_to_cell(1.0, 1.025)
(20, 20)
>>> float(cmap.ml()[20, 20])  # the beam passed through: empty
0.0
>>> float(cmap.ml()[20, 31])  # just behind its end point: covered
1.0
"""

from __future__ import annotations

from covmap._errors import (
    ArrayDtypeError,
    ArrayShapeError,
    CellOutOfBoundsError,
    CovmapError,
    InvalidBearingError,
    InvalidGridError,
    InvalidHistogramError,
    InvalidParameterError,
    InvalidPoseError,
    InvalidRangeError,
    LengthMismatchError,
    PoseOutsideMapError,
)
from covmap._native import (
    DEFAULT_BINS,
    MAX_BINS,
    MIN_BINS,
    CoverageMap,
    Grid,
    LaserModel,
    OccupancyGrid,
    SonarModel,
    __version__,
)

__all__ = [
    "DEFAULT_BINS",
    "MAX_BINS",
    "MIN_BINS",
    "ArrayDtypeError",
    "ArrayShapeError",
    "CellOutOfBoundsError",
    "CoverageMap",
    "CovmapError",
    "Grid",
    "InvalidBearingError",
    "InvalidGridError",
    "InvalidHistogramError",
    "InvalidParameterError",
    "InvalidPoseError",
    "InvalidRangeError",
    "LaserModel",
    "LengthMismatchError",
    "OccupancyGrid",
    "PoseOutsideMapError",
    "SonarModel",
    "__version__",
]
