"""``covmap table1``: the paper's Table I, coverage maps against scan counting."""

from __future__ import annotations

from typing import TYPE_CHECKING

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
    "Explore a world (a built-in one, a generated building, a world file) with 24 simulated sonars by "
    "each strategy of the paper's "
    "Table I (coverage maps with alpha 0.5, scan counting with n = 1 and with n = 50 and long "
    "beams discounted) and by nearest frontiers, once per seed (seeds 0 to K - 1). Prints the "
    "mean and spread of the path length and of the evaluation cells left uncertain beside the "
    "paper's figures, with the maps' errors and the wall time, and writes table1.csv (one row "
    "per run) and table1.png (path length against uncertain cells). With --buildings, the table is a view "
    "of the benchmark: every run in every building named (sets such as test, or buildings), in parallel "
    "(one a local core, or on Dask), the figures over all of them."
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
    _options.add_buildings(command)
    _options.add_dask(command)
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

    seeds = list(range(args.seeds))
    if args.buildings is not None:
        return _run_buildings(args, seeds)
    world = _options.world_building(args).world
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


def _run_buildings(args: argparse.Namespace, seeds: list[int]) -> int:
    """Table I over ``--buildings``: every run through the sweep."""
    from covmap._sweep import RunSummary, SweepFailure
    from covmap._progress import Progress
    from covmap.experiments import table1
    from covmap.plot import plot_table1

    chosen = _options.chosen_buildings(args)
    total = len(chosen) * len(seeds) * len(table1.METHODS)
    with Progress(total, "run") as progress, _options.executor(args) as executor:

        def show(index: int, outcome: RunSummary | SweepFailure) -> None:
            if isinstance(outcome, SweepFailure):
                progress.update(f"spec {index} failed: {outcome.error_type}")
                return
            progress.update(
                f"{outcome.world}, {outcome.strategy!r}: {outcome.path_length_m:.1f} m, "
                f"{100.0 * outcome.high_entropy_fraction:.1f} % uncertain"
            )

        t = table1.run_buildings(
            chosen, seeds=seeds, executor=executor, progress=show, **_options.run_limits(args)
        )
    print(table1.table(t))
    print(f"wrote {table1.write_csv(t, args.out / 'table1.csv')}")
    print(f"wrote {plot_table1(t, args.out / 'table1.png')}")
    return 0
