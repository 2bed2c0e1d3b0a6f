"""``covmap explore``: a simulated robot explores a world until it is done."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from covmap._native import DEFAULT_DISCOUNT_BEYOND_M, Laser, SonarRing, Strategy
from covmap.cli import _options
from covmap.experiments.exploration import MAX_FRAMES

if TYPE_CHECKING:
    import argparse

    from covmap._exploration import Step
    from covmap._native import Exploration

NAME = "explore"
"""The command's name: ``covmap explore``."""

HELP = "a simulated robot explores a world until its strategy is done"
"""The command's line in ``covmap --help``."""

DESCRIPTION = (
    "A disc robot with 24 simulated sonars (or a laser) starts at --start or at a free pose drawn from "
    "the seed in a world (a built-in one, a generated building, a world file), scans, chooses where to "
    "look next with the strategy (coverage: the paper's eq. 14; counting: scan counting to n; frontier: "
    "nearest frontier), drives there scanning on the way, and stops when the strategy is done or at a "
    "limit. Shows its progress, prints a summary (with the rooms never entered), saves what a user needs "
    "to continue (WORLD-STRATEGY.npz: the final posterior, CoverageMap.load; WORLD-STRATEGY.yaml + .pgm: "
    "the ML map as a ROS map_server pair; WORLD-STRATEGY-trajectory.csv: every pose, and whether a scan "
    "was taken there), and draws WORLD-STRATEGY-map.png (the ML map with the trajectory and the scan "
    "points over the true outlines), WORLD-STRATEGY-entropy.png (entropy and uncertain cells) and "
    "WORLD-STRATEGY.gif (the run), with a progress line. Exits 1 if the run ended at a limit "
    "(--max-steps, --max-path-m) rather than by its strategy's rule."
)
"""What ``covmap explore --help`` says the command does."""


def add_arguments(command: argparse.ArgumentParser) -> None:
    """The command's arguments."""
    _options.add_world(command)
    command.add_argument(
        "--strategy",
        choices=("coverage", "counting", "frontier"),
        default="coverage",
        help="how the robot chooses where to go next (default coverage)",
    )
    command.add_argument(
        "--alpha",
        type=_options.weight,
        default=0.5,
        help="coverage: weight of information against travel in [0, 1] (default 0.5)",
    )
    command.add_argument(
        "--n",
        type=_options.positive_int,
        default=50,
        help="counting: interceptions that make a cell explored, at most 1000000 (default 50)",
    )
    command.add_argument(
        "--discount-beyond-m",
        type=_options.discount,
        metavar="M",
        help="counting: beams reading d beyond M metres count M / d (default: no discount; "
        f"Table I's n = 50 row: {DEFAULT_DISCOUNT_BEYOND_M:g})",
    )
    _options.add_seed(command)
    command.add_argument(
        "--sensor",
        choices=("sonar", "laser"),
        default="sonar",
        help="24 sonars all around, or a 180-degree laser of 361 beams (default sonar)",
    )
    command.add_argument(
        "--start",
        type=_options.start_pose,
        metavar="X,Y[,THETA]",
        help="where the robot starts, metres (and its heading, radians; default 0); default: a free "
        "pose drawn from the seed in the largest region the world encloses",
    )
    command.add_argument(
        "--resolution",
        type=_options.length,
        default=0.05,
        help="the maps' cell size, metres (default 0.05)",
    )
    command.add_argument(
        "--epsilon",
        type=_options.entropy,
        default=0.65,
        help="entropy below which a cell is certain, nats, more than 0 (default 0.65)",
    )
    _options.add_out(command, NAME)
    command.add_argument(
        "--record",
        type=Path,
        metavar="FILE.rrd",
        help="also write a recording for the Rerun viewer: every step's maps, robot, beams, goal and the "
        "candidates' gains (needs covmap[rerun]; open it with: rerun FILE.rrd)",
    )
    _options.add_run_limits(command)
    command.add_argument(
        "--frames",
        type=_options.frame_count,
        default=MAX_FRAMES,
        help=f"most frames of the animation, 2 to {_options.MAX_FRAMES} (default {MAX_FRAMES})",
    )


def file_name(building: str) -> str:
    """A building's name as a file name: ``generated:3:120`` as
    ``generated-3-120``, a plan's file name without its suffix."""
    if building.startswith("generated:"):
        return building.replace(":", "-")
    return Path(building).stem or building


def strategy(args: argparse.Namespace) -> Strategy:
    """The strategy the arguments name."""
    if args.strategy == "coverage":
        return Strategy.coverage(args.alpha)
    if args.strategy == "counting":
        return Strategy.counting(args.n, args.discount_beyond_m)
    return Strategy.frontier()


def outputs(args: argparse.Namespace) -> list[Path]:
    """The files the command writes, named after the world and the
    strategy: the posterior, the map_server pair, the trajectory, the map,
    the entropy and the animation."""
    from covmap.experiments.exploration import saved_paths
    from covmap.plot.exploration import exploration_paths

    stem = f"{file_name(args.world)}-{args.strategy}"
    return saved_paths(args.out, stem) + exploration_paths(args.out, stem) + ([args.record] if args.record else [])


def run(args: argparse.Namespace) -> int:
    """Explore, print the summary, save the maps and the trajectory and draw
    the run; 1 unless it ended by its strategy's rule (rather than at a
    limit)."""
    from covmap._progress import Progress
    from covmap.experiments import exploration
    from covmap.plot import plot_exploration

    building = _options.world_building(args)
    sensor = SonarRing() if args.sensor == "sonar" else Laser.sick_361()
    name = file_name(building.name)
    recorder = None
    if args.record is not None:
        from covmap._record import Recorder, exploration_frame

    with Progress(None, "step") as progress:

        def show(run_: Exploration, step: Step) -> None:
            nonlocal recorder
            if args.record is not None:
                if recorder is None:
                    recorder = Recorder(args.record, run_.map.grid, building.world)
                exploration_frame(recorder, run_, step, sensor, building.world)
            progress.update(
                f"{run_.path_length_m:.1f} m, {run_.scans} scans, "
                f"{100.0 * run_.uncertain_fraction:.1f} % uncertain"
            )

        result = exploration.run(
            building.world,
            strategy(args),
            world_name=name,
            frames=args.frames,
            progress=show,
            seed=args.seed,
            sensor=sensor,
            start=args.start,
            resolution=args.resolution,
            epsilon=args.epsilon,
            **_options.run_limits(args),
        )
    if recorder is not None:
        recorder.close()
    print(exploration.summary(result, building=building))
    stem = f"{name}-{result.result.strategy.name}"
    for path in exploration.save(result, args.out, stem):
        print(f"wrote {path}")
    for path in plot_exploration(result, args.out, progress=True):
        print(f"wrote {path}")
    if result.result.termination == "limit":
        print("the run ended at a limit, not by its strategy's rule")
        return 1
    return 0
