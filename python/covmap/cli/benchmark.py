"""``covmap benchmark``: the exploration benchmark, strategies x sensors x
buildings x seeds."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from covmap.cli import _options

if TYPE_CHECKING:
    import argparse

NAME = "benchmark"
"""The command's name: ``covmap benchmark``."""

HELP = "explore many buildings with every strategy: the exploration benchmark"
"""The command's line in ``covmap --help``."""

DESCRIPTION = (
    "Explore buildings with each strategy (coverage maps, scan counting to 1 and to 50, nearest frontier) "
    "and sensor, once per seed, every run in parallel (one a local core, or on Dask), with a progress bar. "
    "Prints a summary per strategy and sensor (median and interquartile range of the evaluation cells left "
    "uncertain, the path length, the rooms never entered and the real-time factor; runs at most 1 % "
    "uncertain, runs that entered every room; how the runs ended) and the real-time factor by building "
    "size, and writes benchmark.csv (one row a run) "
    "and benchmark.png. The default: four small development buildings, the four strategies, sonar, seed 0 "
    "(a few minutes on two cores). --full: 24 test buildings of 120, 250 and 550 square metres and the "
    "real plans (AMROffice, the Stata basement, Willow; from --plans) with sonar, the eight small ones with "
    "the laser too (at most 300 m a laser run); runs on a Dask cluster when given one (--dask). Every "
    "run stops at 3000 m (--max-path-m, --max-steps: other limits for every run). --buildings picks other buildings: sets "
    "(default, development, test) or buildings by name (corridor, office, generated:SEED[:AREA], a world "
    "file), separated by commas. --model maps with a sensor model covmap learn fitted, to judge it on "
    "buildings it was not fitted on. --clear-no-echo integrates as the paper does: no-echo readings clear "
    "their whole footprint, echoes mark their whole arc. --report CSV prints the summary of an earlier run's benchmark.csv and "
    "draws its figure, running nothing."
)
"""What ``covmap benchmark --help`` says the command does."""


def add_arguments(command: argparse.ArgumentParser) -> None:
    """The command's arguments."""
    from covmap.buildings import DEFAULT_PLANS_DIR
    from covmap.experiments.benchmark import STRATEGIES

    command.add_argument(
        "--report",
        type=Path,
        metavar="CSV",
        help="run nothing: print the summary of an earlier run's benchmark.csv and draw its figure into --out",
    )
    command.add_argument(
        "--full",
        action="store_true",
        help="the full benchmark: 24 test buildings and the real plans, sonar and laser",
    )
    command.add_argument(
        "--buildings",
        type=_options.names,
        metavar="NAME,...",
        help="sets (default, development, test) or buildings (corridor, office, generated:SEED[:AREA], "
        "a world file), separated by commas (default: the configuration's)",
    )
    command.add_argument(
        "--count",
        type=_options.positive_int,
        help="generated buildings in each set named (default: 4 in default, 12 in development and test, "
        "24 with --full)",
    )
    command.add_argument(
        "--strategies",
        type=_options.names,
        metavar="NAME,...",
        default=list(STRATEGIES),
        help=f"strategies, separated by commas (default all: {', '.join(STRATEGIES)})",
    )
    command.add_argument(
        "--sensors",
        type=_options.names,
        metavar="NAME,...",
        help="sensors, separated by commas: sonar, laser (default: sonar; with --full both)",
    )
    command.add_argument(
        "--seeds",
        type=_options.positive_int,
        default=1,
        help="runs per building, strategy and sensor, seeds 0 to K - 1 (default 1)",
    )
    command.add_argument(
        "--resolution",
        type=_options.length,
        default=0.05,
        help="the maps' cell size, metres (default 0.05)",
    )
    command.add_argument(
        "--plans",
        default=str(DEFAULT_PLANS_DIR),
        metavar="DIR",
        help=f"where the test set's real plans are read from (default {DEFAULT_PLANS_DIR})",
    )
    command.add_argument(
        "--model",
        metavar="JSON",
        help="a sensor model file of covmap learn: the runs with its sensor map with it "
        "(default: each sensor's default model)",
    )
    command.add_argument(
        "--clear-no-echo",
        action="store_true",
        help="integrate as the paper does: every reading with no echo clears its whole footprint and every "
        "echo marks its whole arc (default: scans read against the cells the coverage map is certain are "
        "covered: a no-echo reading clears only what its line of sight reaches past them, an echo off one "
        "of them marks only the cells at its bearing)",
    )
    _options.add_dask(command)
    _options.add_out(command, NAME)
    _options.add_run_limits(command)


def outputs(args: argparse.Namespace) -> list[Path]:
    """The files the command writes: the CSV (unless it reports an earlier
    one) and the figure."""
    figure = args.out / "benchmark.png"
    return [figure] if args.report is not None else [args.out / "benchmark.csv", figure]


def run(args: argparse.Namespace) -> int:
    """Run the benchmark, print its summary, write its CSV and figure."""
    from covmap._sweep import RunSummary, SweepFailure
    from covmap.buildings import buildings
    from covmap._progress import Progress
    from covmap.experiments import benchmark, benchmark_files
    from covmap.plot import plot_benchmark

    if args.report is not None:
        b = benchmark_files.read_csv(args.report)
        print(benchmark.summary_table(b))
        print(benchmark.speed_table(b))
        (figure,) = outputs(args)
        print(f"wrote {plot_benchmark(b, figure)}")
        return 0
    config = benchmark.CONFIGURATIONS["full" if args.full else "default"]
    references = args.buildings if args.buildings is not None else [config.buildings]
    count = args.count if args.count is not None else config.count
    sensors = args.sensors if args.sensors is not None else list(config.sensors)
    for name in sensors:
        benchmark.sensor_of(name)
    model = None
    if args.model is not None:
        from covmap._errors import InvalidValueError
        from covmap._native import SonarModel

        model = _options.load_model(args.model)
        kind = "sonar" if isinstance(model, SonarModel) else "laser"
        if kind not in sensors:
            raise InvalidValueError(
                f"{args.model}: a {kind} model, but the benchmark runs {', '.join(sensors)} only (--sensors)"
            )
    chosen = buildings(references, count=count, plans=config.plans or args.buildings is not None, plans_dir=args.plans)
    # The configuration's limits per sensor; --max-steps and --max-path-m
    # over all of them.
    given = _options.run_limits(args)
    sensor_options = {name: {**config.sensor_options.get(name, {"max_path_m": benchmark.MAX_PATH_M}), **given} for name in sensors}
    if model is not None:
        sensor_options[kind]["model"] = model
    max_extent = config.max_extent_m2 if args.full else {}
    total = len(
        benchmark.specs(chosen, strategies=args.strategies, sensors=sensors, seeds=[0], max_extent_m2=max_extent)
    ) * args.seeds
    with Progress(total, "run") as progress, _options.executor(args) as executor:

        def show(index: int, outcome: RunSummary | SweepFailure) -> None:
            if isinstance(outcome, SweepFailure):
                progress.update(f"spec {index} failed: {outcome.error_type}")
                return
            progress.update(
                f"{outcome.world}, {outcome.strategy!r}: {outcome.path_length_m:.0f} m, "
                f"{100.0 * outcome.high_entropy_fraction:.1f} % uncertain, {outcome.seconds:.0f} s"
            )

        b = benchmark.run(
            chosen,
            strategies=args.strategies,
            sensors=sensors,
            seeds=list(range(args.seeds)),
            sensor_options=sensor_options,
            max_extent_m2=max_extent,
            executor=executor,
            progress=show,
            resolution=args.resolution,
            **({"occlude_no_echo": False} if args.clear_no_echo else {}),
        )
    print(benchmark.summary_table(b))
    print(benchmark.speed_table(b))
    csv_path, figure = outputs(args)
    print(f"wrote {benchmark_files.write_csv(b, csv_path)}")
    print(f"wrote {plot_benchmark(b, figure)}")
    return 0
