"""Worlds, maps and trajectories drawn into matplotlib axes.

Every function draws into ``ax`` (a new figure's axes when ``None``) and
returns the axes; coordinates are world metres, x to the right and y up.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from covmap._errors import ArrayShapeError

if TYPE_CHECKING:
    import numpy.typing as npt
    from matplotlib.axes import Axes
    from matplotlib.colors import Colormap

    from covmap._native import Grid, World

MATERIAL_COLORS = {"wall": "dimgray", "glass": "lightskyblue"}
"""Fill colour of each material in :func:`plot_world`."""

UNKNOWN_COLOR = "lightsteelblue"
"""Colour of the cells no evidence reached (unknown) in :func:`plot_map`: no
grey level, so that an unknown cell cannot be read as free (an unobserved
cell's ML coverage is 0, as a free cell's is) or as a coverage at all."""


def unknown_colormap(cmap: Any) -> Colormap:
    """``cmap`` (a name or a colormap) whose "bad" colour, the colour of
    masked cells, is :data:`UNKNOWN_COLOR`, unless the colormap already has a
    visible one of its own (matplotlib's default is transparent, which shows
    the white background: unknown cells would look free)."""
    import matplotlib

    colormap = matplotlib.colormaps[cmap] if isinstance(cmap, str) else cmap
    if colormap.get_bad()[3] == 0.0:
        colormap = colormap.with_extremes(bad=UNKNOWN_COLOR)
    return colormap


def _axes(ax: Axes | None) -> Axes:
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    _, new = plt.subplots()
    return new


def plot_world(
    world: World,
    ax: Axes | None = None,
    *,
    colors: dict[str, str] | None = None,
    edgecolor: str = "black",
    linewidth: float = 0.5,
    alpha: float = 1.0,
) -> Axes:
    """Draw the obstacles of ``world``, filled by material (``colors`` maps
    ``"wall"`` and ``"glass"`` to colours; holes are left open), with equal
    axis scales."""
    from matplotlib.patches import PathPatch
    from matplotlib.path import Path as MplPath

    ax = _axes(ax)
    fills = {**MATERIAL_COLORS, **(colors or {})}
    for exterior, holes, material in zip(world.polygons, world.holes, world.materials):
        vertices: list[npt.NDArray[np.float64]] = []
        codes: list[npt.NDArray[np.uint8]] = []
        for ring in (exterior, *holes):
            closed = np.vstack([ring, ring[:1]])
            ring_codes = np.full(len(closed), MplPath.LINETO, dtype=np.uint8)
            ring_codes[0] = MplPath.MOVETO
            ring_codes[-1] = MplPath.CLOSEPOLY
            vertices.append(closed)
            codes.append(ring_codes)
        path = MplPath(np.vstack(vertices), np.concatenate(codes))
        ax.add_patch(
            PathPatch(
                path,
                facecolor=fills[material],
                edgecolor=edgecolor,
                linewidth=linewidth,
                alpha=alpha,
            )
        )
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    return ax


def plot_map(
    values: npt.ArrayLike,
    grid: Grid,
    ax: Axes | None = None,
    *,
    observed: npt.ArrayLike | None = None,
    cmap: Any = "Greys",
    title: str | None = None,
    vmin: float | None = 0.0,
    vmax: float | None = 1.0,
    colorbar: bool = False,
) -> Axes:
    """Draw a per-cell array of ``grid`` (shape ``(rows, cols)``, e.g.
    ``CoverageMap.ml()`` or ``World.coverage(grid)``) as an image over the
    grid's extent: rows run along y, row 0 at the bottom. ``vmin``/``vmax``
    default to the coverage range ``[0, 1]`` (``None``: the data's range).

    Unknown is a value of its own: cells where ``observed`` (a bool array of
    the same shape, e.g. ``CoverageMap.observed()``) is ``False``, and
    masked values, show in :data:`UNKNOWN_COLOR` (or the colormap's own
    visible "bad" colour), never as free."""
    data: np.ma.MaskedArray[Any, Any] = np.ma.asarray(values)
    if data.shape != grid.shape:
        raise ArrayShapeError(f"values of shape {data.shape} do not fit a grid of shape {grid.shape}")
    if observed is not None:
        seen = np.asarray(observed)
        if seen.shape != grid.shape or seen.dtype != np.bool_:
            raise ArrayShapeError(
                f"observed must be a bool array of the grid's shape {grid.shape}, got {seen.dtype} {seen.shape}"
            )
        data = np.ma.masked_where(~seen, data)
    ax = _axes(ax)
    x0, y0, x1, y1 = grid.bounds
    image = ax.imshow(
        data,
        origin="lower",
        extent=(x0, x1, y0, y1),
        cmap=unknown_colormap(cmap),
        vmin=vmin,
        vmax=vmax,
        interpolation="nearest",
    )
    if colorbar:
        ax.figure.colorbar(image, ax=ax, fraction=0.046, pad=0.04)
    if title is not None:
        ax.set_title(title)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    return ax


def plot_trajectory(
    poses_or_xy: npt.ArrayLike,
    ax: Axes | None = None,
    *,
    color: str = "tab:red",
    label: str | None = None,
    headings: bool = False,
    linewidth: float = 1.0,
) -> Axes:
    """Draw a path through ``poses_or_xy`` (shape ``(N, 2)`` of ``(x, y)`` or
    ``(N, 3)`` of ``(x, y, theta)``), its start as a circle and its end as a
    square; with ``headings`` (poses only), an arrow along each heading."""
    points = np.asarray(poses_or_xy, dtype=np.float64)
    if points.ndim != 2 or points.shape[1] not in (2, 3):
        raise ArrayShapeError(f"poses_or_xy must have shape (N, 2) or (N, 3), got {points.shape}")
    ax = _axes(ax)
    if len(points) == 0:
        return ax
    x, y = points[:, 0], points[:, 1]
    ax.plot(x, y, color=color, linewidth=linewidth, label=label)
    ax.plot(x[:1], y[:1], marker="o", color=color, linestyle="none")
    ax.plot(x[-1:], y[-1:], marker="s", color=color, linestyle="none")
    if headings and points.shape[1] == 3:
        theta = points[:, 2]
        ax.quiver(x, y, np.cos(theta), np.sin(theta), color=color, angles="xy", width=0.003)
    return ax
