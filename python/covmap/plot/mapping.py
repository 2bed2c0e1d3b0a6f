"""The figure of a mapped log (``covmap map``): the coverage map's ML,
mean and entropy maps and the occupancy baseline, side by side, unknown
cells in their own colour."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from covmap.plot.drawing import plot_map, plot_trajectory
from covmap.plot.figures import _figure_file

if TYPE_CHECKING:
    from pathlib import Path

    from covmap._native import CoverageMap
    from covmap.experiments.mapping import MappingRun


def plot_mapping(run: MappingRun, path: Path) -> list[Path]:
    """Draw ``run``'s four maps with the robot's path into ``path`` (PNG);
    returns the files written."""
    cmap, grid = run.coverage, run.grid
    observed = cmap.observed()
    panels = (
        (cmap.ml(), observed, "coverage map: maximum likelihood", 0.0, 1.0),
        (cmap.mean(), observed, "coverage map: mean", 0.0, 1.0),
        (cmap.entropy(), None, "coverage map: entropy [nats]", 0.0, math.log(cmap.bins)),
        (run.occupancy.probabilities(), run.occupancy.observed(), "occupancy grid: p(occupied)", 0.0, 1.0),
    )
    rows, cols = grid.shape
    width = 7.0
    height = max(2.5, width * rows / max(cols, 1))
    with _figure_file(path, 2, 2, figsize=(2 * width, 2 * height)) as (_, axes):
        for ax, (values, seen, title, vmin, vmax) in zip(axes.flat, panels):
            plot_map(values, grid, ax, observed=seen, title=title, vmin=vmin, vmax=vmax, colorbar=True)
            plot_trajectory(run.log.poses, ax)
    return [path]


def plot_posterior(cmap: CoverageMap, path: Path) -> list[Path]:
    """Draw a coverage map's ML coverage, mean and entropy side by side
    (as :func:`plot_mapping` draws them) into ``path`` (PNG); returns the
    files written."""
    grid = cmap.grid
    observed = cmap.observed()
    panels = (
        (cmap.ml(), observed, "maximum likelihood", 0.0, 1.0),
        (cmap.mean(), observed, "mean", 0.0, 1.0),
        (cmap.entropy(), None, "entropy [nats]", 0.0, math.log(cmap.bins)),
    )
    rows, cols = grid.shape
    width = 6.0
    height = max(2.5, width * rows / max(cols, 1))
    with _figure_file(path, 1, 3, figsize=(3 * width, height)) as (_, axes):
        for ax, (values, seen, title, vmin, vmax) in zip(axes.flat, panels):
            plot_map(values, grid, ax, observed=seen, title=title, vmin=vmin, vmax=vmax, colorbar=True)
    return [path]
