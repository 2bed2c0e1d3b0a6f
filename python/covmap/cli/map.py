"""``covmap map``: a recorded log into a coverage map and the occupancy
baseline, with the pictures, the map_server pair and the posterior file."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING

from covmap.cli import _options
from covmap._progress import Progress

if TYPE_CHECKING:
    from covmap.experiments import mapping

RECORDED_SCANS = 2000
"""About the most scans a ``--record`` recording draws (every k-th of a
longer log)."""

NAME = "map"
"""The command's name: ``covmap map``."""

HELP = "map a recorded log (CARMEN, plain-text sonar or a ROS bag) into a coverage map"
"""The command's line in ``covmap --help``."""

DESCRIPTION = (
    "Read LOG (a CARMEN log, plain or gzip; with --format sonar-text a poses file and "
    "its --measurements file; with --format rosbag a ROS 1 .bag file or a ROS 2 bag "
    "directory, one LaserScan or Range --topic of it, which needs covmap[rosbags]), integrate every scan into a coverage map and into the "
    "occupancy-grid baseline over a grid that holds the log, and write to --out: "
    "coverage.npz (the whole posterior, CoverageMap.load reads it), map.yaml + map.pgm "
    "(the ML map for ROS map_server), occupancy.yaml + occupancy.pgm (the baseline), and "
    "the pictures maps.png (ML, mean, entropy and the baseline). Prints a summary. "
    "A plain-text sonar log says nothing of its units or sonars: give them (--bearings, --max-range, "
    "and where they are not metres and radians --length-unit, --range-unit, --angle-unit; --min-range "
    "and --no-echo for the readings that are not echoes). The sonar-8ring data set, for example: "
    "--bearings=-90,-37.5,-22.5,-7.5,7.5,22.5,37.5,90 --length-unit 0.001 --angle-unit 0.1deg "
    "--min-range 0.17 --max-range 5 --no-echo 5110."
)
"""What ``covmap map --help`` says the command does."""


def add_arguments(command: argparse.ArgumentParser) -> None:
    """The command's arguments."""
    command.add_argument("log", type=Path, metavar="LOG", help="the log file (for sonar-text: its poses file)")
    command.add_argument(
        "--format",
        choices=("carmen", "sonar-text", "rosbag"),
        default=None,
        help="the log's format (default: sonar-text with --measurements, rosbag for a .bag file "
        "or a directory, else carmen)",
    )
    sonar = command.add_argument_group("plain-text sonar logs (--format sonar-text; see covmap.Log.from_sonar_text)")
    sonar.add_argument("--measurements", type=Path, default=None, help="the log's measurements file")
    sonar.add_argument(
        "--bearings",
        type=_options.bearings,
        default=None,
        metavar="DEG,...|FILE",
        help="each measurement column's sonar, degrees from the heading: a list separated by commas "
        "(--bearings=-90,0,90) or a file of numbers; required",
    )
    sonar.add_argument(
        "--length-unit",
        type=_options.unit,
        default=1.0,
        metavar="M",
        help="metres per unit of the poses' x and y (0.001: millimetres; default 1)",
    )
    sonar.add_argument(
        "--range-unit",
        type=_options.unit,
        default=None,
        metavar="M",
        help="metres per unit of the ranges (default: --length-unit)",
    )
    sonar.add_argument(
        "--angle-unit",
        type=_options.angle_unit,
        default=1.0,
        metavar="UNIT",
        help="the heading's unit: rad, deg, a number of radians, or a number of degrees with deg "
        "(0.1deg: tenths of a degree); default rad",
    )
    sonar.add_argument(
        "--min-range",
        type=_options.reading_bound,
        default=0.0,
        metavar="M",
        help="readings shorter than this are dropped, metres (default 0)",
    )
    sonar.add_argument(
        "--no-echo",
        type=_options.reading,
        default=None,
        metavar="VALUE",
        help="the reading, in the file's units, a sonar writes when it heard no echo (default: none; "
        "readings at or above --max-range have none either)",
    )
    command.add_argument(
        "--laser",
        choices=("front", "rear"),
        default="front",
        help="a CARMEN log's laser: front (FLASER, ROBOTLASER1, RAWLASER1) or rear (RLASER, "
        "ROBOTLASER2, RAWLASER2); default front",
    )
    bag = command.add_argument_group("ROS bags (--format rosbag; see covmap.Log.from_bag)")
    bag.add_argument("--topic", default=None, help="the LaserScan or Range topic (default: the bag's only one)")
    bag.add_argument(
        "--odom-topic", default=None, help="the nav_msgs/Odometry topic of the poses (default: poses from /tf)"
    )
    bag.add_argument("--base-frame", default=None, help="the robot's frame (default: base_link)")
    bag.add_argument("--fixed-frame", default=None, help="the poses' frame in /tf (default: the tree's root)")
    command.add_argument(
        "--sensor",
        choices=("laser", "sonar"),
        default=None,
        help="the sensor model (default: sonar for sonar-text and for a bag's Range topic, else laser)",
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
        "--max-range",
        type=_options.distance,
        default=None,
        help="the log's maximum range, metres (a sonar-text log's, required; else overrides the log's)",
    )
    _options.add_out(command, NAME)
    command.add_argument(
        "--record",
        type=Path,
        metavar="FILE.rrd",
        help="also write a recording for the Rerun viewer: the robot's path and every scan's beams over the "
        "scans, the maps' layers at the end (needs covmap[rerun]; open it with: rerun FILE.rrd)",
    )


def default_format(args: argparse.Namespace) -> mapping.Format:
    """The format ``--format`` defaults to for ``args.log``."""
    if args.measurements is not None:
        return "sonar-text"
    if args.log.suffix == ".bag" or args.log.is_dir():
        return "rosbag"
    return "carmen"


def outputs(args: argparse.Namespace) -> list[Path]:
    """The files the command writes: the posterior, both map_server pairs
    (YAML, then its PGM) and the pictures."""
    names = ("coverage.npz", "map.yaml", "map.pgm", "occupancy.yaml", "occupancy.pgm", "maps.png")
    return [args.out / name for name in names] + ([args.record] if args.record is not None else [])


def run(args: argparse.Namespace) -> int:
    """Map the log, write the files, print the summary."""
    from covmap.experiments import mapping
    from covmap.plot import plot_mapping

    if args.record is not None:
        from covmap._record import _rerun

        _rerun()  # the extra is there, before anything runs
    log_format = args.format or default_format(args)
    log = mapping.read_log(
        args.log,
        log_format=log_format,
        measurements=args.measurements,
        max_range_m=args.max_range,
        topic=args.topic,
        odom_topic=args.odom_topic,
        base_frame=args.base_frame,
        fixed_frame=args.fixed_frame,
        laser=args.laser,
        bearings_deg=args.bearings,
        length_unit_m=args.length_unit,
        range_unit_m=args.range_unit,
        angle_unit_rad=args.angle_unit,
        min_range_m=args.min_range,
        no_echo=args.no_echo,
    )
    # A bag's sensor_msgs/Range log is one beam along the sensor's axis.
    one_sonar = log_format == "rosbag" and log.beams == 1
    sensor: mapping.Sensor = args.sensor or ("sonar" if log_format == "sonar-text" or one_sonar else "laser")
    args.out.mkdir(parents=True, exist_ok=True)
    # One count of the log's scans for each map: the coverage map's, then
    # the occupancy grid's (the callback starts again from the first scan).
    names = iter(("scans into the coverage map", "scans into the occupancy grid"))
    shown = Progress(len(log), next(names))
    try:
        last = 0

        def show(done: int, _total: int) -> None:
            nonlocal last, shown
            if done < last:
                shown.__exit__(None, None, None)
                shown, last = Progress(len(log), next(names, "scans")), 0
            for _ in range(done - last):
                shown.update()
            last = done

        result = mapping.run(log, sensor=sensor, resolution_m=args.resolution, reach_m=args.reach, progress=show)
    finally:
        shown.__exit__(None, None, None)
    print(f"log {args.log} ({log_format})")
    print(mapping.summary(result))
    print(f"agreement    {mapping.agreement(result):.3f} of the cells both maps know")
    coverage, map_yaml, _, occupancy_yaml, _, maps = outputs(args)[:6]
    result.coverage.save(coverage)
    result.coverage.to_ros_map(map_yaml)
    result.occupancy.to_ros_map(occupancy_yaml)
    plot_mapping(result, maps)
    if args.record is not None:
        from covmap._record import record_log

        # At most about 2000 scans drawn: a long log's recording stays small.
        record_log(args.record, log, result.coverage, every=max(1, len(log) // RECORDED_SCANS))
    for path in outputs(args):
        print(f"wrote {path}")
    return 0
