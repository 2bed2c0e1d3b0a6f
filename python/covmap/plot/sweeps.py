"""The figures of sweeps: ``covmap fig7``'s chart, written whole or not at all."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from covmap.plot.figures import _figure_file

__all__ = ["plot_fig7"]

if TYPE_CHECKING:
    from pathlib import Path

    from covmap.experiments.fig7 import Fig7


def plot_fig7(f: Fig7, path: Path) -> Path:
    """Write the paper's Fig. 7 to ``path`` (PNG), atomically: path length
    against the percentage of evaluation cells certain at the end, each
    counting run a dot, the mean per ``n`` a line labelled by ``n``, the
    coverage runs each a small cross and their mean a large cross with its
    spread (sample standard deviation) in both directions, and a dashed line
    through the coverage runs' mean path on the way (where each first had a
    fraction certain, :meth:`Fig7.reaching`). Returns the path."""
    with _figure_file(path, figsize=(7.5, 5.0), layout="constrained") as (_, ax):
        ax.scatter(
            [100.0 * r.certain_fraction for r in f.counting],
            [r.path_length_m for r in f.counting],
            color="tab:blue",
            s=14,
            alpha=0.45,
            label="counting runs",
        )
        curve = f.curve
        ax.plot(
            [100.0 * p.certain for p in curve],
            [p.path_m for p in curve],
            "-o",
            color="tab:blue",
            markersize=4,
            label="counting, mean per n (discounted)",
        )
        for n, p in zip(f.ns, curve):
            ax.annotate(f"{n}", (100.0 * p.certain, p.path_m), textcoords="offset points", xytext=(4, 4), fontsize=7)
        ax.scatter(
            [100.0 * r.certain_fraction for r in f.coverage],
            [r.path_length_m for r in f.coverage],
            marker="x",
            color="tab:red",
            s=18,
            alpha=0.6,
            label="coverage runs",
        )
        if f.coverage:
            from covmap.experiments.fig7 import mean_reached_at

            # From the least any run had certain after its first step to
            # the least any had at its end: where every run has a path.
            low = min(1.0 - float(r.trace["uncertain_fraction"][0]) for r in f.coverage)
            top = min(r.certain_fraction for r in f.coverage)
            way = [(x, mean_reached_at(f.coverage, x)) for x in np.linspace(low, top, 60)]
            way = [(x, p) for x, p in way if p is not None]
            if way:
                ax.plot(
                    [100.0 * x for x, _ in way],
                    [p for _, p in way],
                    "--",
                    color="tab:red",
                    linewidth=1.0,
                    label="coverage runs on the way: mean path at which each first had the fraction",
                )
        c = f.cross
        ax.errorbar(
            [100.0 * c.certain],
            [c.path_m],
            xerr=[100.0 * c.certain_spread],
            yerr=[c.path_spread_m],
            fmt="x",
            color="tab:red",
            markersize=14,
            markeredgewidth=2.5,
            capsize=4,
            label=f"coverage maps, alpha {f.alpha:g}: mean ± sd",
        )
        ax.set_xlabel("evaluation cells certain (H < epsilon) [%]")
        ax.set_ylabel("path length [m]")
        ax.set_title(
            f"Fig. 7, {f.world_name}, {len(f.seeds)} seed(s): scan counting to n against coverage maps",
            fontsize=9,
        )
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    return path
