"""``covmap map``: a recorded log into a coverage map and the occupancy
baseline, with the pictures, the map_server pair and the posterior file."""

from __future__ import annotations

import argparse
from pathlib import Path

from covmap.cli import _options
from covmap.cli._progress import Progress

NAME = "map"
"""The command's name: ``covmap map``."""

HELP = "map a recorded log (CARMEN or plain-text sonar) into a coverage map"
"""The command's line in ``covmap --help``."""

DESCRIPTION = (
    "Read LOG (a CARMEN log, plain or gzip, or with --format sonar-text a poses file and "
    "its --measurements file), integrate every scan into a coverage map and into the "
    "occupancy-grid baseline over a grid that holds the log, and write to --out: "
    "coverage.npz (the whole posterior, CoverageMap.load reads it), map.yaml + map.pgm "
    "(the ML map for ROS map_server), occupancy.yaml + occupancy.pgm (the baseline), and "
    "the pictures maps.png (ML, mean, entropy and the baseline). Prints a summary."
)
"""What ``covmap map --help`` says the command does."""


def add_arguments(command: argparse.ArgumentParser) -> None:
    """The command's arguments."""
    command.add_argument("log", type=Path, metavar="LOG", help="the log file (for sonar-text: its poses file)")
    command.add_argument(
        "--format",
        choices=("carmen", "sonar-text"),
        default=None,
        help="the log's format (default: sonar-text with --measurements, else carmen)",
    )
    command.add_argument("--measurements", type=Path, default=None, help="a sonar-text log's measurements file")
    command.add_argument(
        "--sensor",
        choices=("laser", "sonar"),
        default=None,
        help="the sensor model (default: laser for carmen, sonar for sonar-text)",
    )
    command.add_argument(
        "--resolution", type=_options.length, default=0.05, help="cell size, metres (default 0.05)"
    )
    command.add_argument(
        "--reach",
        type=_options.distance,
        default=10.0,
        help="the grid holds every beam up to this far, metres (default 10)",
    )
    command.add_argument(
        "--max-range", type=_options.distance, default=None, help="override the log's maximum range, metres"
    )
    _options.add_out(command, NAME)


def run(args: argparse.Namespace) -> int:
    """Map the log, write the files, print the summary."""
    from covmap.experiments import mapping
    from covmap.plot import plot_mapping

    log_format = args.format or ("sonar-text" if args.measurements is not None else "carmen")
    sensor = args.sensor or ("sonar" if log_format == "sonar-text" else "laser")
    log = mapping.read_log(
        args.log, log_format=log_format, measurements=args.measurements, max_range_m=args.max_range
    )
    args.out.mkdir(parents=True, exist_ok=True)
    with Progress(2 * len(log), "scans") as progress:
        last = 0

        def show(done: int, total: int) -> None:
            # Called for the coverage map's scans, then the occupancy grid's.
            nonlocal last
            last = 0 if done < last else last
            for _ in range(done - last):
                progress.update("coverage map" if progress.count < total else "occupancy grid")
            last = done

        result = mapping.run(log, sensor=sensor, resolution_m=args.resolution, reach_m=args.reach, progress=show)
    print(f"log {args.log} ({log_format})")
    print(mapping.summary(result))
    print(f"agreement    {mapping.agreement(result):.3f} of the cells both maps know")
    written = [args.out / "coverage.npz", args.out / "map.yaml", args.out / "occupancy.yaml"]
    result.coverage.save(written[0])
    result.coverage.to_ros_map(written[1])
    result.occupancy.to_ros_map(written[2])
    written += [args.out / "map.pgm", args.out / "occupancy.pgm"]
    written += plot_mapping(result, args.out / "maps.png")
    for path in written:
        print(f"wrote {path}")
    return 0
