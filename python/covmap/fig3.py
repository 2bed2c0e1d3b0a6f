"""The paper's Fig. 3: a coverage map of a corridor built from ultrasound.

:func:`covmap.run_fig3` drives 24 simulated sonars along a seeded path through
the built-in ``corridor`` and measures the coverage map and an occupancy grid
fed by the same readings against the exact ground truth. This module prints
its figures and draws its maps.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from covmap.plot import plot_map, plot_trajectory, save_figure

if TYPE_CHECKING:
    from pathlib import Path

MAPS = (
    ("truth", "ground truth: exact coverage"),
    ("ml", "coverage map: maximum likelihood"),
    ("occupancy", "occupancy grid: p(occupied)"),
)
"""The maps drawn, as (key of the result, title)."""


def table(result: dict[str, Any], seed: int) -> str:
    """The figures of a :func:`covmap.run_fig3` result as text."""
    poses = result["poses"]
    lines = [
        f"Fig. 3, corridor, 24 sonars, seed {seed}: {len(poses)} poses, "
        f"{result['readings']} readings, {result['cells_reached']} cells reached",
        f"{'mean absolute error':<22}  {'all reached':>11}  {'partly covered':>14}",
    ]
    for key, name in (
        ("mae_ml", "coverage map, ML"),
        ("mae_mean", "coverage map, mean"),
        ("mae_occupancy", "occupancy grid"),
    ):
        errors = result[key]
        lines.append(f"{name:<22}  {errors['all']:>11.4f}  {errors['partial']:>14.4f}")
    lines.append(
        f"log-likelihood of the truth: {result['log_likelihood']:.1f} "
        f"(uniform prior: {result['log_likelihood_prior']:.1f})"
    )
    return "\n".join(lines)


def plot(result: dict[str, Any], out: Path) -> list[Path]:
    """Write one PNG per map of :data:`MAPS` into ``out`` (``fig3-truth.png``,
    ``fig3-ml.png``, ``fig3-occupancy.png``), atomically; returns the paths.
    Cells no reading reached are drawn light blue in the estimated maps; the
    path is drawn over the ground truth."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    grid = result["grid"]
    greys = matplotlib.colormaps["Greys"].with_extremes(bad="lightsteelblue")
    written = []
    for key, title in MAPS:
        values = result[key]
        if key != "truth":
            values = np.ma.masked_where(~result["reached"], values)
        rows, cols = grid.shape
        fig, ax = plt.subplots(figsize=(max(6.0, cols / 28), max(2.5, rows / 28 + 1.0)), layout="constrained")
        try:
            plot_map(values, grid, ax, cmap=greys, title=f"Fig. 3, {title}", colorbar=True)
            if key == "truth":
                plot_trajectory(result["poses"], ax, color="tab:red", linewidth=0.8)
            written.append(save_figure(fig, out / f"fig3-{key}.png"))
        finally:
            plt.close(fig)
    return written
