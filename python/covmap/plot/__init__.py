"""Drawing worlds, maps and trajectories with matplotlib, and the figures of
the paper's experiments.

matplotlib is imported inside the functions, so ``import covmap`` does not pay
for it. The drawing functions (``plot_world``, ``plot_map``,
``plot_trajectory``) draw into ``ax`` (a new figure's axes when ``None``) and
return the axes; coordinates are world metres, x to the right and y up.
``save_figure`` writes a figure to a PNG file atomically. The figures of the
experiments (``plot_fig1``, ``plot_fig3``, ``plot_planning_step``,
``plot_world_and_coverage``) are drawn and written to PNG files whole, as the
``covmap`` command writes them.

>>> import matplotlib
>>> matplotlib.use("Agg")
>>> import matplotlib.pyplot as plt
>>> import covmap
>>> world = covmap.World.builtin("partial")
>>> grid = covmap.Grid(origin=(1.5, -1.5), resolution=0.05, shape=(60, 30))
>>> ax = covmap.plot.plot_map(world.coverage(grid), grid, title="ground truth")
>>> ax = covmap.plot.plot_world(world, ax=ax)
>>> [float(x) for x in ax.get_xlim()]  # the map's extent: the grid's bounds
[1.5, 3.0]
>>> plt.close(ax.figure)
"""

from covmap.plot.drawing import MATERIAL_COLORS, plot_map, plot_trajectory, plot_world
from covmap.plot.figures import (
    plot_fig1,
    plot_fig3,
    plot_planning_step,
    plot_world_and_coverage,
)
from covmap.plot.saving import save_figure

__all__ = [
    "MATERIAL_COLORS",
    "plot_fig1",
    "plot_fig3",
    "plot_map",
    "plot_planning_step",
    "plot_trajectory",
    "plot_world",
    "plot_world_and_coverage",
    "save_figure",
]
