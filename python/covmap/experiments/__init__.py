"""The paper's experiments, reproduced: each computes its figures and leaves
drawing them to :mod:`covmap.plot` and running them to the ``covmap`` command.

- :mod:`~covmap.experiments.fig1`: a cell partly covered by an obstacle,
  coverage map against occupancy grid (laser);
- :mod:`~covmap.experiments.fig3`: a corridor mapped with simulated sonars,
  measured against the exact ground truth (the result of :func:`covmap.run_fig3`);
- :mod:`~covmap.experiments.planning_step`: one step of exploration, where to
  look next after a few scans.
"""

from covmap.experiments import fig1, fig3, planning_step

__all__ = ["fig1", "fig3", "planning_step"]
