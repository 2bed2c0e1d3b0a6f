"""``covmap table1``: the paper's Table I, coverage maps against scan counting."""

from __future__ import annotations

from typing import TYPE_CHECKING

from covmap._native import World
from covmap.cli import _options

if TYPE_CHECKING:
    import argparse
    from pathlib import Path

    from covmap._exploration import ExplorationResult
    from covmap.experiments.table1 import Method

NAME = "table1"
"""The command's name: ``covmap table1``."""

HELP = "reproduce Table I: exploration with coverage maps against scan counting"
"""The command's line in ``covmap --help``."""

DESCRIPTION = (
    "Explore a built-in world with 24 simulated sonars by each strategy of the paper's "
    "Table I (coverage maps with alpha 0.5, scan counting with n = 1 and with n = 50 and long "
    "beams discounted) and by nearest frontiers, once per seed (seeds 0 to K - 1). Prints the "
    "mean and spread of the path length and of the evaluation cells left uncertain beside the "
    "paper's figures, with the maps' errors and the wall time, and writes table1.csv (one row "
    "per run) and table1.png (path length against uncertain cells)."
)
"""What ``covmap table1 --help`` says the command does."""


def add_arguments(command: argparse.ArgumentParser) -> None:
    """The command's arguments."""
    _options.add_world(command)
    command.add_argument(
        "--seeds",
        type=_options.positive_int,
        default=3,
        help="runs per strategy, seeds 0 to K - 1, at most 1000000 (default 3)",
    )
    _options.add_out(command, NAME)
    _options.add_run_limits(command)


def outputs(args: argparse.Namespace) -> list[Path]:
    """The files the command writes: the table and its chart."""
    return [args.out / "table1.csv", args.out / "table1.png"]


def run(args: argparse.Namespace) -> int:
    """Run the table, print it, write its CSV and chart."""
    from covmap._progress import Progress
    from covmap.experiments import table1
    from covmap.plot import plot_table1

    world = World.builtin(args.world)
    seeds = list(range(args.seeds))
    with Progress(len(seeds) * len(table1.METHODS), "run") as progress:

        def show(method: Method, seed: int, result: ExplorationResult) -> None:
            progress.update(
                f"{method.label}, seed {seed}: {result.path_length_m:.1f} m, "
                f"{100.0 * result.high_entropy_fraction:.1f} % uncertain, {result.seconds:.1f} s"
            )

        t = table1.run(world, world_name=args.world, seeds=seeds, progress=show, **_options.run_limits(args))
    print(table1.table(t))
    csv_path, chart_path = outputs(args)
    print(f"wrote {table1.write_csv(t, csv_path)}")
    print(f"wrote {plot_table1(t, chart_path)}")
    return 0
