"""The figures of exploration runs: ``covmap explore``'s maps and animation
and ``covmap table1``'s chart, each written whole or not at all."""

from __future__ import annotations

import io
import math
from typing import TYPE_CHECKING, Any

import numpy as np

from covmap._native import Grid
from covmap.plot.drawing import UNKNOWN_COLOR, plot_map, plot_trajectory, plot_world, unknown_colormap
from covmap.plot.figures import _figure_file

__all__ = ["plot_exploration", "plot_table1", "save_animation"]

if TYPE_CHECKING:
    from pathlib import Path

    from matplotlib.axes import Axes

    from covmap._exploration import ExplorationResult
    from covmap._native import World
    from covmap.experiments.exploration import ExploreRun, Snapshot
    from covmap.experiments.table1 import Table1

GIF_FRAME_MS = 150
"""How long each frame of an exploration's animation shows, milliseconds."""

GIF_LAST_FRAME_MS = 2000
"""How long the last frame (the run's end) shows, milliseconds."""


def _size(grid: Grid, width: float = 9.0) -> tuple[float, float]:
    """A figure size of ``width`` inches that fits the grid's aspect."""
    x0, y0, x1, y1 = grid.bounds
    return width, max(2.5, width * (y1 - y0) / (x1 - x0) + 1.0)


def _outline(world: World, ax: Axes) -> None:
    """The true obstacles' outlines, over a map: every ring one line of a
    single collection (one artist, however many polygons a plan holds)."""
    from matplotlib.collections import LineCollection

    rings = [np.vstack([ring, ring[:1]]) for ring in world.polygons]
    rings += [np.vstack([hole, hole[:1]]) for holes in world.holes for hole in holes]
    ax.add_collection(LineCollection(rings, colors="tab:orange", linewidths=0.6, alpha=0.8))
    ax.set_aspect("equal")


def _robot_path(trajectory: Any, ax: Axes, scanned: Any | None = None) -> None:
    """The trajectory, and the scan points where given."""
    plot_trajectory(trajectory, ax, color="tab:red", linewidth=0.8, label="path")
    if scanned is not None:
        points = trajectory[scanned]
        ax.plot(points[:, 0], points[:, 1], ".", color="tab:blue", markersize=2.5, label="scans")


PNG_DPI = 100
"""The pixels an inch of the runs' PNGs (:func:`~covmap.plot.save_figure`'s)."""


def _thinned(grid: Grid, width_px: float, height_px: float) -> tuple[int, Grid]:
    """A stride and the grid of every ``stride``-th cell of ``grid`` (in
    rows and columns), the stride the least that leaves no more cells than
    ``width_px`` by ``height_px`` pixels: a large plan's map is thinned as
    nearest-neighbour drawing would pick its cells, before it is drawn
    (1 and ``grid`` itself where the grid fits)."""
    rows, cols = grid.shape
    stride = max(1, math.ceil(max(cols / width_px, rows / height_px)))
    if stride == 1:
        return 1, grid
    x0, y0, _, _ = grid.bounds
    shape = (math.ceil(rows / stride), math.ceil(cols / stride))
    return stride, Grid(origin=(x0, y0), resolution=stride * grid.resolution, shape=shape)


def _fit(ax: Axes, grid: Grid) -> None:
    x0, y0, x1, y1 = grid.bounds
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)


def exploration_paths(out: Path, name: str) -> list[Path]:
    """The files :func:`plot_exploration` writes into ``out`` for a run
    called ``name``: the map, the entropy and the animation."""
    return [out / f"{name}-map.png", out / f"{name}-entropy.png", out / f"{name}.gif"]


def plot_exploration(run: ExploreRun, out: Path, name: str | None = None, *, progress: bool = False) -> list[Path]:
    """Write the figures of a ``covmap explore`` run into ``out``, each
    atomically, files named ``<name>-...`` (default: world and strategy),
    with a progress line on standard error if ``progress``:

    - ``-map.png``: the final ML map (unknown cells in
      :data:`~covmap.plot.drawing.UNKNOWN_COLOR`), the true obstacles'
      outlines, the trajectory and the scan points;
    - ``-entropy.png``: the entropy map, and the evaluation cells with the
      uncertain ones (entropy above epsilon) marked;
    - ``.gif``: the run as an animation of its snapshots.

    Returns the paths."""
    r = run.result
    name = name or f"{run.world_name}-{r.strategy.name}"
    title = f"{run.world_name}, {r.strategy!r}, seed {r.seed}"
    map_path, entropy_path, animation_path = exploration_paths(out, name)
    w, h = _size(r.grid)
    stride, grid = _thinned(r.grid, w * PNG_DPI, h * PNG_DPI)
    written = []
    path = map_path
    with _figure_file(path, figsize=(w, h), layout="constrained") as (_, ax):
        plot_map(r.map.ml()[::stride, ::stride], grid, ax, observed=r.map.observed()[::stride, ::stride], colorbar=True)
        _outline(run.world, ax)
        _robot_path(r.trajectory, ax, r.scanned)
        _fit(ax, grid)
        ax.set_title(
            f"{title}: ML coverage (unknown: light blue), {r.path_length_m:.1f} m, {r.scans} scans, {r.termination}",
            fontsize=9,
        )
        ax.legend(loc="upper right", fontsize=7)
    written.append(path)

    path = entropy_path
    entropy = r.map.entropy()
    with _figure_file(path, 2, 1, figsize=(w, 2 * h - 0.5), layout="constrained") as (fig, (ent_ax, unc_ax)):
        plot_map(
            entropy[::stride, ::stride],
            grid,
            ent_ax,
            cmap="viridis",
            vmin=0.0,
            vmax=math.log(r.map.bins),
            colorbar=True,
        )
        ent_ax.set_title(f"{title}: entropy [nats]", fontsize=9)
        # 0: outside the evaluation cells, 1: evaluation cell, certain, 2: uncertain.
        uncertain = r.evaluation_cells & (entropy.astype(np.float64) > r.epsilon)  # ExplorationResult.uncertain_cells
        classes = np.where(uncertain, 2.0, np.where(r.evaluation_cells, 1.0, 0.0))
        from matplotlib.colors import ListedColormap

        plot_map(
            classes[::stride, ::stride],
            grid,
            unc_ax,
            cmap=ListedColormap(["white", "lightgray", "tab:red"]),
            vmin=0.0,
            vmax=2.0,
        )
        unc_ax.set_title(
            f"uncertain (H > {r.epsilon:g} nats, red): {100.0 * r.high_entropy_fraction:.2f} % of the "
            f"evaluation cells (grey)",
            fontsize=9,
        )
        for ax in (ent_ax, unc_ax):
            _outline(run.world, ax)
            _fit(ax, grid)
    written.append(path)

    written.append(save_animation(run.frames, r, run.world, animation_path, title=title, progress=progress))
    return written


def save_animation(
    frames: list[Snapshot],
    result: ExplorationResult,
    world: World,
    path: Path,
    *,
    title: str = "",
    progress: bool = False,
) -> Path:
    """Write ``frames`` (snapshots of the run ``result`` in ``world``) as an
    animated GIF to ``path``, atomically: the ML map with unknown cells in
    :data:`~covmap.plot.drawing.UNKNOWN_COLOR`, the true outlines and the
    path so far, one frame a snapshot, the last held longer; a progress
    line on standard error with ``progress``. The figure is drawn once and
    each frame changes only the map, the path and the title (the outlines
    of a large plan are not drawn again for every frame). Drawn with the Agg
    backend and encoded by Pillow (which matplotlib depends on) in memory,
    then written by the same atomic writer as the PNGs. Returns the path."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from PIL import Image

    from covmap._native import write_atomic
    from covmap._progress import Progress

    dpi = 80
    w, h = _size(result.grid, 6.0)
    fig, ax = plt.subplots(figsize=(w, h), dpi=dpi, layout="constrained")
    # A frame shows no more cells than it has pixels: a large plan's map is
    # thinned (every ``stride``-th cell, as nearest-neighbour drawing would
    # pick them), and the true outlines are baked into its colours once,
    # so that a frame redraws one small image, the path and the title.
    stride, thinned = _thinned(result.grid, w * dpi, h * dpi)
    x0, y0, x1, y1 = thinned.bounds
    colours = _FrameColours(world, thinned)
    images = []

    def caption(snap: Snapshot) -> str:
        return (
            f"{title}: step {snap.step}, {snap.path_length_m:.1f} m, "
            f"{100.0 * snap.uncertain_fraction:.1f} % uncertain"
        )

    try:
        picture = ax.imshow(
            colours.of(frames[0].ml[::stride, ::stride]),
            origin="lower",
            extent=(x0, x1, y0, y1),
            interpolation="nearest",
            animated=True,
        )
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        (path_line,) = ax.plot([], [], color="tab:red", linewidth=0.8, animated=True)
        _fit(ax, result.grid)
        ax.set_aspect("equal")
        heading = ax.set_title(caption(frames[-1]), fontsize=8)
        fig.canvas.draw()
        # The layout is made once, and the axes, ticks and labels drawn once
        # (the background every frame starts from).
        fig.set_layout_engine("none")
        heading.set_animated(True)
        fig.canvas.draw()
        background = fig.canvas.copy_from_bbox(fig.bbox)
        with Progress(len(frames), "frame") if progress else _Quiet() as shown:
            for snap in frames:
                fig.canvas.restore_region(background)
                picture.set_data(colours.of(snap.ml[::stride, ::stride]))
                path_line.set_data(snap.trajectory[:, 0], snap.trajectory[:, 1])
                heading.set_text(caption(snap))
                for artist in (picture, path_line, heading):
                    ax.draw_artist(artist)
                rgba = np.asarray(fig.canvas.buffer_rgba())
                frame = Image.fromarray(rgba[:, :, :3].copy())
                images.append(frame.quantize(colors=64, method=Image.Quantize.MEDIANCUT))
                shown.update(f"drawing {path.name}")
    finally:
        plt.close(fig)
    durations = [GIF_FRAME_MS] * (len(images) - 1) + [GIF_LAST_FRAME_MS]
    gif = io.BytesIO()
    images[0].save(gif, format="GIF", save_all=True, append_images=images[1:], duration=durations, loop=0)
    path.parent.mkdir(parents=True, exist_ok=True)
    write_atomic(path, gif.getvalue())
    return path


class _FrameColours:
    """The colours of an animation's frames on ``grid``: ML levels as greys
    (:data:`~covmap.experiments.exploration.LEVELS` black), unknown cells
    in :data:`~covmap.plot.drawing.UNKNOWN_COLOR`, and over both the cells
    on the edge of the true obstacles in orange."""

    def __init__(self, world: World, grid: Grid) -> None:
        from matplotlib.colors import to_rgb

        from covmap.experiments.exploration import LEVELS, UNKNOWN_LEVEL

        inside = world.coverage(grid) > 0.0
        padded = np.pad(inside, 1, constant_values=False)
        interior = padded[:-2, 1:-1] & padded[2:, 1:-1] & padded[1:-1, :-2] & padded[1:-1, 2:]
        self.edge = inside & ~interior
        table = np.zeros((256, 3), dtype=np.uint8)
        greys = np.clip(np.rint(255.0 * (1.0 - np.arange(256) / LEVELS)), 0, 255).astype(np.uint8)
        table[:, 0] = table[:, 1] = table[:, 2] = greys
        table[UNKNOWN_LEVEL] = [round(255 * c) for c in to_rgb(UNKNOWN_COLOR)]
        self.table = table
        self.orange = np.array([round(255 * c) for c in to_rgb("tab:orange")], dtype=np.uint8)

    def of(self, levels: Any) -> Any:
        """The RGB image of ``levels`` (a snapshot's ``ml``, thinned to the grid)."""
        rgb = self.table[levels]
        rgb[self.edge[: levels.shape[0], : levels.shape[1]]] = self.orange
        return rgb


class _Quiet:
    """No progress display."""

    def __enter__(self) -> _Quiet:
        return self

    def __exit__(self, *exc: object) -> None:
        pass

    def update(self, status: str) -> None:
        """Nothing."""


def plot_table1(t: Table1, path: Path) -> Path:
    """Write Table I as a chart to ``path`` (PNG), atomically: each run's path
    length against the uncertain share of its evaluation cells, a marker per
    method, the methods' means circled, the paper's figures as stars of the
    same colour; path lengths on a log scale. Returns the path."""
    colors = ["tab:green", "tab:orange", "tab:blue", "tab:purple"]
    with _figure_file(path, figsize=(7.5, 5.0), layout="constrained") as (_, ax):
        for row, color in zip(t.rows, colors):
            m = row.method
            paths = [r.path_length_m for r in row.runs]
            uncertain = [100.0 * r.uncertain_fraction for r in row.runs]
            ax.scatter(paths, uncertain, color=color, s=22, alpha=0.7, label=f"{m.label} (runs)")
            ax.scatter(
                [row.stat("path_length_m")[0]],
                [100.0 * row.stat("uncertain_fraction")[0]],
                facecolors="none",
                edgecolors=color,
                s=140,
                linewidths=1.5,
            )
            if m.paper_path_m is not None and m.paper_uncertain is not None:
                ax.scatter(
                    [m.paper_path_m],
                    [100.0 * m.paper_uncertain],
                    marker="*",
                    color=color,
                    edgecolors="black",
                    linewidths=0.5,
                    s=180,
                    label=f"{m.label} (paper)",
                )
        ax.set_xscale("log")  # from tens of metres (counting n = 1) to kilometres
        ax.set_xlabel("path length [m], log scale")
        ax.set_ylabel("evaluation cells with H > epsilon [%]")
        ax.set_title(
            f"Table I, {t.world_name}, {len(t.seeds)} seed(s): runs (dots), their means (circles), the paper (stars)",
            fontsize=9,
        )
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    return path
