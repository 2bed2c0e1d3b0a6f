"""``covmap fig7``: the paper's Fig. 7, scan counting to each n against coverage maps."""

from __future__ import annotations

from typing import TYPE_CHECKING

from covmap.cli import _options

if TYPE_CHECKING:
    import argparse
    from pathlib import Path

    from covmap._native import Building

NAME = "fig7"
"""The command's name: ``covmap fig7``."""

HELP = "reproduce Fig. 7: path length against certain cells, scan counting to n against coverage maps"
"""The command's line in ``covmap --help``."""

DEFAULT_SEEDS = 4
"""Runs per n and of the coverage strategy (the issue's default sweep)."""

DEFAULT_RESOLUTION_M = 0.05
"""The maps' cell size of the default sweep, metres: ``covmap.explore``'s and
the paper's. At 0.1 m the runs take a quarter of the time, but sonar arcs
close the built-in corridor's 0.9 m doorways on maps that coarse, and most
counting runs end in the part of the building they started in
(BENCHMARKS.md, Fig. 7)."""

DESCRIPTION = (
    "Explore a world (a built-in one, a generated building, a world file) with 24 simulated sonars by "
    "scan counting forced to each count n "
    "(long beams discounted beyond 2 m, as in Table I) and by coverage maps (alpha A), once per "
    "seed (seeds 0 to K - 1), all runs in parallel: one a local core, or on Dask (--dask "
    "ADDRESS, a running scheduler; --dask-local WORKERS, a cluster started here). Shows a "
    "progress bar, prints the counting curve (the mean per n) and the coverage runs' mean, "
    "where the curve passes the coverage runs' mean path, and both strategies' path lengths "
    "at 85, 90 and 95 % certain cells (read off the counting curve by linear interpolation), "
    "and writes fig7.png and fig7.csv (one row per run). The default sweep: 11 values of n, "
    f"{DEFAULT_SEEDS} seeds, {DEFAULT_RESOLUTION_M:g} m cells as covmap explore's (--resolution 0.1 "
    "runs four times as fast on maps too coarse for the corridor's doorways). With --buildings, the figure "
    "is a view of the benchmark: every n and the coverage runs in every building named (sets such as "
    "test, or buildings), each point the mean over the buildings and seeds."
)
"""What ``covmap fig7 --help`` says the command does."""


def _ns(text: str) -> list[int]:
    import argparse

    values = []
    for part in text.split(","):
        try:
            value = _options.positive_int(part.strip())
        except argparse.ArgumentTypeError:
            raise argparse.ArgumentTypeError(
                f"expected counts from 1 to {_options.MAX_COUNT} separated by commas, got {text}"
            ) from None
        values.append(value)
    if len(set(values)) != len(values):
        raise argparse.ArgumentTypeError(f"expected distinct counts, got {text}")
    return values


def add_arguments(command: argparse.ArgumentParser) -> None:
    """The command's arguments."""
    from covmap.experiments.fig7 import DEFAULT_NS, MAX_PATH_M

    _options.add_world(command)
    command.add_argument(
        "--ns",
        type=_ns,
        default=list(DEFAULT_NS),
        metavar="N,N,...",
        help=f"the counts n of scan counting, separated by commas (default {','.join(map(str, DEFAULT_NS))})",
    )
    command.add_argument(
        "--seeds",
        type=_options.positive_int,
        default=DEFAULT_SEEDS,
        help=f"runs per n and of coverage maps, seeds 0 to K - 1, at most 1000000 (default {DEFAULT_SEEDS})",
    )
    command.add_argument(
        "--alpha",
        type=_options.weight,
        default=0.5,
        help="coverage maps' weight of information against travel in [0, 1] (default 0.5)",
    )
    command.add_argument(
        "--resolution",
        type=_options.length,
        default=DEFAULT_RESOLUTION_M,
        help=f"the maps' cell size, metres (default {DEFAULT_RESOLUTION_M:g}, as covmap explore's)",
    )
    _options.add_buildings(command)
    _options.add_dask(command)
    _options.add_out(command, NAME)
    _options.add_run_limits(command, max_path_m=MAX_PATH_M)


def outputs(args: argparse.Namespace) -> list[Path]:
    """The files the command writes: the table and the figure."""
    return [args.out / "fig7.csv", args.out / "fig7.png"]


def run(args: argparse.Namespace) -> int:
    """Run the sweep, print its comparison, write its CSV and figure."""
    from covmap._sweep import RunSummary, SweepFailure
    from covmap._progress import Progress
    from covmap.experiments import fig7
    from covmap.plot import plot_fig7

    seeds = list(range(args.seeds))
    if args.buildings is not None:
        worlds: list[Building] = _options.chosen_buildings(args)
    else:
        worlds = [_options.world_building(args)]
    total = (len(args.ns) + 1) * len(seeds) * len(worlds)
    with Progress(total, "run") as progress, _options.executor(args) as executor:

        def show(index: int, outcome: RunSummary | SweepFailure) -> None:
            if isinstance(outcome, SweepFailure):
                progress.update(f"spec {index} failed: {outcome.error_type}")
                return
            s = outcome.strategy
            label = f"n = {s.n}" if s.name == "counting" else s.name
            progress.update(
                f"{outcome.world}, {label}, seed {outcome.seed}: {outcome.path_length_m:.1f} m, "
                f"{100.0 * outcome.certain_fraction:.1f} % certain"
            )

        f = fig7.run(
            worlds,
            ns=args.ns,
            seeds=seeds,
            alpha=args.alpha,
            executor=executor,
            progress=show,
            resolution=args.resolution,
            **_options.run_limits(args),
        )
    print(fig7.report(f))
    csv_path, figure_path = outputs(args)
    print(f"wrote {fig7.write_csv(f, csv_path)}")
    print(f"wrote {plot_fig7(f, figure_path)}")
    return 0
