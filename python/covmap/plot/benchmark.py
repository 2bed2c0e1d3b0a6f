"""The figure of the exploration benchmark (``covmap benchmark``), written
whole or not at all."""

from __future__ import annotations

from typing import TYPE_CHECKING

from covmap.plot.figures import _figure_file

__all__ = ["plot_benchmark"]

if TYPE_CHECKING:
    from pathlib import Path

    from covmap.experiments.benchmark import Benchmark

COLORS = ("tab:green", "tab:orange", "tab:blue", "tab:purple", "tab:red", "tab:brown")
"""A colour a strategy, in the summary's order."""


def plot_benchmark(b: Benchmark, path: Path) -> Path:
    """Write the benchmark as a figure to ``path`` (PNG), atomically: for
    each strategy and sensor, the uncertain share of the evaluation cells
    and the path length of every run (box plots: median, quartiles,
    whiskers to 1.5 times the interquartile range, the runs beyond as
    dots), and every run's path length against its uncertain share, one
    colour a strategy (filled: sonar, hollow: laser; larger: a run that
    missed rooms). Returns the path."""
    summaries = b.summaries()
    keys = [(s.strategy, s.sensor) for s in summaries]
    strategies = list(dict.fromkeys(s.strategy for s in summaries))
    color = {name: COLORS[i % len(COLORS)] for i, name in enumerate(strategies)}
    labels = [f"{s}\n{n}" for s, n in keys]
    runs = [[r for r in b.runs if (r.strategy, r.sensor) == k] for k in keys]
    with _figure_file(path, 1, 3, figsize=(15.0, 4.8), layout="constrained") as (fig, (unc, dist, scatter)):
        for ax, values, name in (
            (unc, [[100.0 * r.uncertain_fraction for r in group] for group in runs], "uncertain [%]"),
            (dist, [[r.path_length_m for r in group] for group in runs], "path length [m]"),
        ):
            boxes = ax.boxplot(values, patch_artist=True, widths=0.6)
            ax.set_xticks(range(1, len(labels) + 1), labels, fontsize=7)
            for patch, (strategy, _) in zip(boxes["boxes"], keys):
                patch.set_facecolor(color[strategy])
                patch.set_alpha(0.5)
            ax.set_ylabel(name)
            ax.grid(alpha=0.3, axis="y")
        # Shares from hundredths of a percent to all (the whole range, so
        # that a few close values still get ticks); paths from metres to
        # kilometres.
        unc.set_yscale("symlog", linthresh=1.0)
        unc.set_ylim(0.0, 100.0)
        dist.set_yscale("log")
        unc.set_title("evaluation cells uncertain at the end", fontsize=9)
        dist.set_title("path length", fontsize=9)
        for (strategy, sensor), group in zip(keys, runs):
            missed = [r.rooms_missed > 0 for r in group]
            scatter.scatter(
                [r.path_length_m for r in group],
                [100.0 * r.uncertain_fraction for r in group],
                s=[40 if m else 14 for m in missed],
                facecolors=color[strategy] if sensor == "sonar" else "none",
                edgecolors=color[strategy],
                alpha=0.7,
                label=f"{strategy}, {sensor}",
            )
        scatter.set_xscale("log")
        scatter.set_yscale("symlog", linthresh=1.0)
        scatter.set_ylim(0.0, 100.0)
        scatter.set_xlabel("path length [m]")
        scatter.set_ylabel("uncertain [%]")
        scatter.set_title("every run (larger: rooms never entered)", fontsize=9)
        scatter.grid(alpha=0.3)
        scatter.legend(fontsize=7)
        buildings = len({r.building for r in b.runs})
        n = len(b.runs)
        fig.suptitle(
            f"Exploration benchmark: {n} run{'' if n == 1 else 's'} on {buildings} building{'' if buildings == 1 else 's'}",
            fontsize=10,
        )
    return path
