"""The figures of the experiments and of the ``covmap`` command, each drawn
with the Agg backend and written to PNG files by :func:`save_figure`."""

from __future__ import annotations

import math
from contextlib import contextmanager
from typing import TYPE_CHECKING, Any

import numpy as np

from covmap.plot.drawing import plot_map, plot_trajectory, plot_world, unknown_colormap
from covmap.plot.saving import save_figure

if TYPE_CHECKING:
    from collections.abc import Iterator, Sequence
    from pathlib import Path

    import numpy.typing as npt
    from matplotlib.colors import Colormap
    from matplotlib.figure import Figure

    from covmap._native import Grid, World
    from covmap.experiments.fig1 import Run
    from covmap.experiments.fig3 import Fig3Result
    from covmap.experiments.planning_step import Step

FIG3_MAPS = (
    ("truth", "ground truth: exact coverage"),
    ("ml", "coverage map: maximum likelihood"),
    ("occupancy", "occupancy grid: p(occupied)"),
)
"""The maps :func:`plot_fig3` draws, as (attribute of the result, title)."""


@contextmanager
def _figure_file(path: Path, *args: Any, **kwargs: Any) -> Iterator[tuple[Figure, Any]]:
    """A new figure and its axes (``plt.subplots(*args, **kwargs)``, Agg
    backend) to draw in; written to ``path`` when the block ends, and closed
    either way."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(*args, **kwargs)
    try:
        yield fig, axes
        save_figure(fig, path)
    finally:
        plt.close(fig)


def _greys_unobserved() -> Colormap:
    """Grey levels for coverage; masked (unobserved) cells light blue
    (:data:`~covmap.plot.drawing.UNKNOWN_COLOR`)."""
    return unknown_colormap("Greys")


def plot_fig1(runs: Sequence[Run], path: Path) -> Path:
    """Write the figure of :func:`covmap.experiments.fig1.run_all`'s runs to
    ``path`` (PNG) atomically, one row per run: the occupancy probabilities
    and the ML coverage around the target cell, and the target cell's
    histogram. Returns the path."""
    from matplotlib.patches import Rectangle

    from covmap.experiments.fig1 import RESOLUTION_M, TARGET, grid

    g = grid()
    row, col = TARGET
    r = RESOLUTION_M
    window = 5  # cells on each side of the target
    rows = slice(row - window, row + window + 1)
    cols = slice(col - window, col + window + 1)
    x0, y0 = g.origin
    extent = (
        x0 + (col - window) * r,
        x0 + (col + window + 1) * r,
        y0 + (row - window) * r,
        y0 + (row + window + 1) * r,
    )
    with _figure_file(path, len(runs), 3, figsize=(11, 3.4 * len(runs)), squeeze=False) as (fig, axes):
        for ax_row, run_ in zip(axes, runs):
            occ_ax, ml_ax, hist_ax = ax_row
            # The ML value of an unobserved cell (uniform prior) is 0 like an empty
            # cell's: show those cells apart.
            ml_shown = np.ma.masked_where(~run_.observed, run_.ml_map)
            for ax, data, title in (
                (occ_ax, run_.occupancy_map, "occupancy probability"),
                (ml_ax, ml_shown, "ML coverage (unobserved: blue)"),
            ):
                image = ax.imshow(
                    data[rows, cols], origin="lower", extent=extent, vmin=0.0, vmax=1.0, cmap=_greys_unobserved()
                )
                ax.add_patch(
                    Rectangle((x0 + col * r, y0 + row * r), r, r, fill=False, edgecolor="tab:red", lw=1.5)
                )
                ax.axvline(run_.x_face_m, color="tab:blue", lw=1.0, ls="--")
                ax.set_title(f"f = {run_.fraction:.1f}: {title}", fontsize=9)
                ax.set_xlabel("x [m]")
                ax.set_ylabel("y [m]")
                fig.colorbar(image, ax=ax, fraction=0.046, pad=0.04)
            width = 0.8 / (len(run_.bin_values) - 1)
            hist_ax.bar(run_.bin_values, run_.histogram, width=width, color="tab:gray")
            hist_ax.axvline(run_.fraction, color="tab:blue", ls="--", label="true coverage")
            hist_ax.set_xlim(-0.05, 1.05)
            hist_ax.set_xlabel("coverage")
            hist_ax.set_ylabel("probability")
            hist_ax.set_title(
                f"target cell: ML {run_.ml:.3f}, mean {run_.mean:.3f}, p(occ) {run_.occupancy:.3f}",
                fontsize=9,
            )
            hist_ax.legend(fontsize=8)
        fig.suptitle("Fig. 1: a cell partly covered by an obstacle (laser)")
        fig.tight_layout()
    return path


def plot_fig3(result: Fig3Result, out: Path) -> list[Path]:
    """Write one PNG per map of :data:`FIG3_MAPS` of a :func:`covmap.run_fig3`
    result into ``out`` (``fig3-truth.png``, ``fig3-ml.png``,
    ``fig3-occupancy.png``), atomically; returns the paths. Cells no reading
    reached are drawn light blue in the estimated maps; the path is drawn over
    the ground truth."""
    grid = result.grid
    written = []
    for (key, title), path in zip(FIG3_MAPS, fig3_paths(out)):
        values = getattr(result, key)
        if key != "truth":
            values = np.ma.masked_where(~result.reached, values)
        rows, cols = grid.shape
        with _figure_file(
            path, figsize=(max(6.0, cols / 28), max(2.5, rows / 28 + 1.0)), layout="constrained"
        ) as (_, ax):
            plot_map(values, grid, ax, cmap=_greys_unobserved(), title=f"Fig. 3, {title}", colorbar=True)
            if key == "truth":
                plot_trajectory(result.poses, ax, color="tab:red", linewidth=0.8)
        written.append(path)
    return written


def fig3_paths(out: Path) -> list[Path]:
    """The files :func:`plot_fig3` writes into ``out``, in its order."""
    return [out / f"fig3-{key}.png" for key, _ in FIG3_MAPS]


def world_paths(name: str, out: Path) -> list[Path]:
    """The files :func:`plot_world_and_coverage` writes into ``out`` for a
    world called ``name``: the obstacles and the coverage."""
    return [out / f"{name}-{kind}.png" for kind in ("world", "coverage")]


def plot_world_and_coverage(
    world: World, grid: Grid, coverage: npt.NDArray[np.float64], name: str, out: Path
) -> list[Path]:
    """Write ``world``'s obstacles (``<name>-world.png``) and its exact
    ``coverage`` on ``grid`` (``<name>-coverage.png``) into ``out``,
    atomically, at a size that follows the world's bounds; returns the paths."""
    x0, y0, x1, y1 = world.bounds
    scale = 8.0 / max(x1 - x0, y1 - y0)
    size = (max(4.0, (x1 - x0) * scale + 1.5), max(3.0, (y1 - y0) * scale + 1.0))
    written = []
    for kind, path in zip(("world", "coverage"), world_paths(name, out)):
        with _figure_file(path, figsize=size, layout="constrained") as (_, ax):
            if kind == "world":
                plot_world(world, ax)
                ax.set_title(f"{name}: {len(world)} obstacles (glass light blue)")
            else:
                plot_map(coverage, grid, ax, title=f"{name}: exact coverage, {grid.resolution:g} m cells", colorbar=True)
        written.append(path)
    return written


def plot_planning_step(step: Step, path: Path) -> Path:
    """Write a :mod:`planning step <covmap.experiments.planning_step>` as a
    PNG of two panels, atomically: the ML map (cells no reading changed in
    light blue, :data:`~covmap.plot.drawing.UNKNOWN_COLOR`), and the expected gain of every candidate over the entropy
    map, with the start, the chosen viewpoint and the path. Both panels show
    the observed part of the map. Returns the path."""
    cmap, grid, plan = step.coverage_map, step.grid, step.plan
    entropy = cmap.entropy()
    observed = cmap.observed()
    rows_seen, cols_seen = np.nonzero(observed)
    gx0, gy0 = grid.origin
    r = grid.resolution
    if len(rows_seen):
        view = (
            gx0 + cols_seen.min() * r - 1.0,
            gx0 + (cols_seen.max() + 1) * r + 1.0,
            gy0 + rows_seen.min() * r - 1.0,
            gy0 + (rows_seen.max() + 1) * r + 1.0,
        )
    else:
        x0, y0, x1, y1 = grid.bounds
        view = (x0, x1, y0, y1)
    wide = (view[1] - view[0]) > 1.5 * (view[3] - view[2])
    with _figure_file(
        path, 2 if wide else 1, 1 if wide else 2, figsize=(10, 8) if wide else (13, 5.5), layout="constrained"
    ) as (fig, axes):
        ml_ax, gain_ax = axes
        plot_map(np.ma.masked_where(~observed, cmap.ml()), grid, ml_ax, cmap=_greys_unobserved(), colorbar=True)
        ml_ax.set_title(f"ML coverage after {step.scans} sonar scans (unobserved: blue)", fontsize=10)
        plot_map(entropy, grid, gain_ax, cmap="Greys_r", vmin=0.0, vmax=math.log(cmap.bins))
        candidates = plan.candidates
        poses = candidates.poses
        dots = gain_ax.scatter(poses[:, 0], poses[:, 1], c=candidates.gains, cmap="viridis", s=28, zorder=3)
        fig.colorbar(dots, ax=gain_ax, fraction=0.046, pad=0.04, label="expected gain [nats]")
        gain_ax.set_title(
            f"expected gain of {len(poses)} candidates over the entropy (alpha {step.planner.alpha:g})",
            fontsize=10,
        )
        for ax in (ml_ax, gain_ax):
            plot_world(step.world, ax, colors={"wall": "none", "glass": "none"}, edgecolor="tab:orange", alpha=0.7)
            ax.plot(step.start[0], step.start[1], marker="o", color="tab:blue", linestyle="none", label="start")
            ax.set_xlim(view[0], view[1])
            ax.set_ylim(view[2], view[3])
        if plan.pose is not None:
            plot_trajectory(plan.path, gain_ax, color="tab:red", label="path")
            gain_ax.plot(
                plan.pose[0],
                plan.pose[1],
                marker="*",
                markersize=16,
                color="tab:red",
                markeredgecolor="white",
                linestyle="none",
                label="chosen viewpoint",
                zorder=4,
            )
        gain_ax.legend(loc="upper right", fontsize=8)
    return path
