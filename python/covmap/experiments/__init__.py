"""The paper's experiments, reproduced: each computes its figures and leaves
drawing them to :mod:`covmap.plot` and running them to the ``covmap`` command.

- :mod:`~covmap.experiments.fig1`: a cell partly covered by an obstacle,
  coverage map against occupancy grid (laser);
- :mod:`~covmap.experiments.fig3`: a corridor mapped with simulated sonars,
  measured against the exact ground truth (the result of :func:`covmap.run_fig3`);
- :mod:`~covmap.experiments.planning_step`: one step of exploration, where to
  look next after a few scans;
- :mod:`~covmap.experiments.exploration`: a whole exploration run watched step
  by step (``covmap explore``), with snapshots for its animation;
- :mod:`~covmap.experiments.table1`: the paper's Table I, coverage maps against
  scan counting (and nearest frontiers) over several seeds;
- :mod:`~covmap.experiments.fig7`: the paper's Fig. 7, scan counting forced
  to each count ``n`` against coverage maps, a sweep (:func:`covmap.sweep`);
- :mod:`~covmap.experiments.benchmark`: the exploration benchmark,
  strategies x sensors x buildings x seeds (``covmap benchmark``), its file in
  :mod:`~covmap.experiments.benchmark_files`; Table I and Fig. 7 are its views
  over any buildings.
"""

from covmap.experiments import (
    benchmark,
    benchmark_files,
    exploration,
    fig1,
    fig3,
    fig7,
    planning_step,
    table1,
)

__all__ = ["benchmark", "benchmark_files", "exploration", "fig1", "fig3", "fig7", "planning_step", "table1"]
