"""Coverage maps for mobile robots (Stachniss and Burgard, 2003).

Every cell of a :class:`CoverageMap` holds a histogram over how much of the
cell is covered by obstacles, updated by Bayes' rule with the inverse sensor
model of a sonar cone (:class:`SonarModel`) or a laser beam
(:class:`LaserModel`). :class:`OccupancyGrid` is the classic baseline fed by
the same beams. :func:`expected_information_gain` and :class:`Planner` choose
where to look next (paper eq. 11-14).

The simulator: a :class:`World` of obstacle polygons with its exact
ground-truth coverage and ray casts, simulated sensors (:class:`SonarRing`,
:class:`Laser`) whose scans feed ``CoverageMap.integrate`` directly, and a
disc :class:`Robot`. A :class:`Log` is a recorded drive (read from CARMEN or
plain-text sonar files, built from ROS LaserScan arrays, or recorded by a
simulated sensor) that ``integrate_log`` maps in one call. :func:`sweep` runs
many explorations at once, on the local cores or on a Dask cluster, and
returns a :class:`RunSummary` of each. :mod:`covmap.plot` draws them with matplotlib.

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

from covmap import plot
from covmap import _errors
from covmap._errors import *  # noqa: F403 (the error classes, listed in _errors.__all__)
from covmap._custom import CustomStrategy, StrategyView
from covmap._exploration import ExplorationErrors, ExplorationResult, Step, Timing
from covmap._executors import dask_client
from covmap._record import record
from covmap._sweep import RunSummary, SweepFailure, sweep
from covmap._native import (
    DEFAULT_BINS,
    DEFAULT_DISCOUNT_BEYOND_M,
    MAP_FILE_VERSION,
    MAX_BINS,
    MIN_BINS,
    STAGNATION_MEASUREMENTS,
    STAGNATION_NATS,
    Building,
    Candidates,
    CoverageMap,
    Door,
    Exploration,
    ExplorationStatus,
    Grid,
    Laser,
    LaserModel,
    Log,
    OccupancyGrid,
    Plan,
    Planner,
    Robot,
    Room,
    SensorFit,
    SonarModel,
    SonarRing,
    Strategy,
    World,
    __version__,
    expected_information_gain,
    explore,
    fit_sensor_model,
    log_likelihood,
    run_fig3,
    run_learn,
)

__all__ = [
    "DEFAULT_BINS",
    "DEFAULT_DISCOUNT_BEYOND_M",
    "MAP_FILE_VERSION",
    "MAX_BINS",
    "MIN_BINS",
    "STAGNATION_MEASUREMENTS",
    "STAGNATION_NATS",
    "Building",
    "Candidates",
    "CoverageMap",
    "CustomStrategy",
    "Door",
    "Exploration",
    "ExplorationErrors",
    "ExplorationResult",
    "ExplorationStatus",
    "Grid",
    "Laser",
    "LaserModel",
    "Log",
    "OccupancyGrid",
    "Plan",
    "Planner",
    "Robot",
    "Room",
    "RunSummary",
    "SensorFit",
    "SonarModel",
    "SonarRing",
    "Step",
    "Strategy",
    "StrategyView",
    "SweepFailure",
    "Timing",
    "World",
    "__version__",
    "dask_client",
    "expected_information_gain",
    "explore",
    "fit_sensor_model",
    "log_likelihood",
    "plot",
    "record",
    "run_fig3",
    "run_learn",
    "sweep",
]
__all__ += _errors.__all__
