"""A recorded log into a coverage map and the occupancy baseline: the grid
that holds the log, both maps fed the same beams, and what they show.

:func:`read_log` reads a CARMEN log, a plain-text sonar log or one sensor
of a ROS bag;
:func:`run` maps it; :func:`summary` says what came out;
:func:`covmap.plot.plot_mapping` draws the maps. ``covmap map`` runs all
four and writes the map files.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Callable, Literal

import numpy as np

from covmap._native import CoverageMap, Grid, LaserModel, Log, OccupancyGrid, SonarModel

if TYPE_CHECKING:
    from collections.abc import Sequence
    from pathlib import Path

Format = Literal["carmen", "sonar-text", "rosbag"]
Sensor = Literal["laser", "sonar"]


def read_log(
    path: Path,
    *,
    log_format: Format,
    measurements: Path | None = None,
    bearings_deg: Sequence[float] | None = None,
    length_unit_m: float = 1.0,
    range_unit_m: float | None = None,
    angle_unit_rad: float = 1.0,
    min_range_m: float = 0.0,
    max_range_m: float | None = None,
    no_echo: float | None = None,
    topic: str | None = None,
    odom_topic: str | None = None,
    base_frame: str | None = None,
    fixed_frame: str | None = None,
    laser: Literal["front", "rear"] = "front",
) -> Log:
    """The log at ``path``: a CARMEN file, (``"sonar-text"``) the poses
    file with its ``measurements`` file, or (``"rosbag"``) a ROS bag's
    ``topic`` as ``Log.from_bag`` reads it (with ``odom_topic``,
    ``base_frame`` and ``fixed_frame``); a CARMEN log's ``laser`` is its
    front or its rear laser. A sonar-text log is described by
    ``bearings_deg`` and ``max_range_m`` (both required), its units and
    the readings that are not echoes, as :meth:`covmap.Log.from_sonar_text`
    takes them."""
    if log_format == "carmen":
        return Log.from_carmen(path, max_range_m=max_range_m, laser=laser)
    if log_format == "rosbag":
        return Log.from_bag(
            path,
            topic=topic,
            odom_topic=odom_topic,
            base_frame=base_frame,
            fixed_frame=fixed_frame,
            max_range_m=max_range_m,
        )
    from covmap._errors import InvalidParameterError

    missing = [
        (name, option)
        for name, option, value in (
            ("measurements", "--measurements FILE", measurements),
            ("bearings_deg", "--bearings DEG,...", bearings_deg),
            ("max_range_m", "--max-range M", max_range_m),
        )
        if value is None
    ]
    if missing:
        raise InvalidParameterError(
            f"{path}: a sonar-text log is a poses file and its measurements file, and says nothing of its "
            f"sonars: give {', '.join(n for n, _ in missing)} (covmap map POSES --format sonar-text "
            f"{' '.join(o for _, o in missing)})"
        )
    assert measurements is not None and bearings_deg is not None and max_range_m is not None
    return Log.from_sonar_text(
        path,
        measurements,
        bearings_deg=list(bearings_deg),
        length_unit_m=length_unit_m,
        range_unit_m=range_unit_m,
        angle_unit_rad=angle_unit_rad,
        min_range_m=min_range_m,
        max_range_m=max_range_m,
        no_echo=no_echo,
    )


def grid_for(log: Log, *, resolution_m: float, reach_m: float, margin_m: float = 0.5) -> Grid:
    """The grid covering every pose of ``log`` and every beam cut at
    ``reach_m``, with ``margin_m`` around."""
    bounds = log.extent(reach_m)
    if bounds is None:
        raise ValueError("the log holds no scan")
    x0, y0, x1, y1 = bounds
    return Grid.covering((x0 - margin_m, y0 - margin_m, x1 + margin_m, y1 + margin_m), resolution=resolution_m)


@dataclass
class MappingRun:
    """A log mapped: the coverage map and the occupancy grid over one grid,
    and the seconds each took to integrate the log."""

    log: Log
    grid: Grid
    coverage: CoverageMap
    occupancy: OccupancyGrid
    sensor: Sensor
    coverage_s: float
    occupancy_s: float


def run(
    log: Log,
    *,
    sensor: Sensor,
    resolution_m: float = 0.05,
    reach_m: float = 10.0,
    progress: Callable[[int, int], object] | bool = False,
) -> MappingRun:
    """Map ``log`` with the ``sensor``'s default model into a coverage map
    and the occupancy baseline over :func:`grid_for`'s grid; ``progress`` as
    ``CoverageMap.integrate_log`` takes it (called for each map)."""
    grid = grid_for(log, resolution_m=resolution_m, reach_m=reach_m)
    model = LaserModel() if sensor == "laser" else SonarModel()
    coverage, occupancy = CoverageMap(grid), OccupancyGrid(grid)
    start = time.perf_counter()
    coverage.integrate_log(log, model, progress=progress)
    middle = time.perf_counter()
    occupancy.integrate_log(log, model, progress=progress)
    end = time.perf_counter()
    return MappingRun(log, grid, coverage, occupancy, sensor, middle - start, end - middle)


def summary(r: MappingRun) -> str:
    """What the mapping did and found, a line a fact."""
    rows, cols = r.grid.shape
    x0, y0, x1, y1 = r.grid.bounds
    data = r.coverage.ros_occupancy()
    known = int((data >= 0).sum())
    lines = [
        f"scans        {len(r.log)} of {r.log.beams} beams, max range {r.log.max_range_m:g} m, {r.sensor} model",
        f"grid         {rows} x {cols} cells (rows x columns) of {r.grid.resolution:g} m over [{x0:.2f}, {x1:.2f}] x [{y0:.2f}, {y1:.2f}] m",
        f"coverage map {r.coverage_s:.2f} s; {known} cells known ({100 * known / data.size:.1f} %), "
        f"{int((data >= 65).sum())} occupied",
        f"occupancy    {r.occupancy_s:.2f} s; {int(r.occupancy.observed().sum())} cells observed, "
        f"{int((r.occupancy.probabilities() > 0.65).sum())} occupied",
    ]
    return "\n".join(lines)


def agreement(r: MappingRun) -> float:
    """The share of the cells both maps know on which they agree, occupied
    (at least 65 %) or not: the coverage map's ML against the occupancy
    grid's probability."""
    a, b = r.coverage.ros_occupancy(), r.occupancy.ros_occupancy()
    both = (a >= 0) & (b >= 0)
    if not both.any():
        return math.nan
    return float(np.mean((a[both] >= 65) == (b[both] >= 65)))
