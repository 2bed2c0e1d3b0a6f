"""Drawing worlds, maps and trajectories with matplotlib, and the figures of
the paper's experiments.

matplotlib is imported inside the functions, so ``import covmap`` does not pay
for it. The drawing functions (``plot_world``, ``plot_map``,
``plot_trajectory``) draw into ``ax`` (a new figure's axes when ``None``) and
return the axes; coordinates are world metres, x to the right and y up.
``save_figure`` writes a figure to a PNG file atomically. Unknown is a value
of its own: ``plot_map`` draws the cells no evidence reached (``observed=``,
e.g. ``CoverageMap.observed()``, or masked values) in ``UNKNOWN_COLOR``,
never as free. The figures of the experiments (``plot_fig1``, ``plot_fig3``,
``plot_planning_step``, ``plot_world_and_coverage``, ``plot_exploration``
with its GIF ``save_animation``, ``plot_table1``, ``plot_mapping``, ``plot_fig7``, ``plot_benchmark``) are drawn and written to
files whole, as the ``covmap`` command writes them.

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

from covmap.plot.benchmark import plot_benchmark
from covmap.plot.drawing import (
    MATERIAL_COLORS,
    UNKNOWN_COLOR,
    plot_map,
    plot_trajectory,
    plot_world,
    unknown_colormap,
)
from covmap.plot.exploration import plot_exploration, plot_table1, save_animation
from covmap.plot.mapping import plot_mapping
from covmap.plot.sweeps import plot_fig7
from covmap.plot.figures import (
    plot_fig1,
    plot_fig3,
    plot_planning_step,
    plot_world_and_coverage,
)
from covmap.plot.saving import save_figure

__all__ = [
    "MATERIAL_COLORS",
    "UNKNOWN_COLOR",
    "plot_benchmark",
    "plot_exploration",
    "plot_fig1",
    "plot_fig3",
    "plot_fig7",
    "plot_map",
    "plot_mapping",
    "plot_planning_step",
    "plot_table1",
    "plot_trajectory",
    "plot_world",
    "plot_world_and_coverage",
    "save_animation",
    "save_figure",
    "unknown_colormap",
]
