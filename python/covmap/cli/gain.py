"""``covmap gain``: one planning step, where to look next after a few scans."""

from __future__ import annotations

from typing import TYPE_CHECKING

from covmap.cli import _options

if TYPE_CHECKING:
    import argparse
    from pathlib import Path

NAME = "gain"
"""The command's name: ``covmap gain``."""

HELP = "expected information gain and the next viewpoint after a few sonar scans"
"""The command's line in ``covmap --help``."""

DESCRIPTION = (
    "Scan a world (a built-in one, a generated building, a world file) a few times with 24 simulated sonars from a free pose near "
    "one end of its main passage, integrate the scans into a coverage map, let the "
    "planner choose the next viewpoint, print it, and write gain.png: the ML map and "
    "the expected gain of every candidate with the chosen viewpoint and its path."
)
"""What ``covmap gain --help`` says the command does."""


def add_arguments(command: argparse.ArgumentParser) -> None:
    """The command's arguments."""
    _options.add_world(command)
    _options.add_out(command, NAME)
    command.add_argument(
        "--scans", type=_options.positive_int, default=3, help="sonar scans, at most 1000000 (default 3)"
    )
    _options.add_seed(command)
    command.add_argument(
        "--alpha",
        type=_options.weight,
        default=0.5,
        help="weight of gain against travel cost in [0, 1] (default 0.5)",
    )


def outputs(args: argparse.Namespace) -> list[Path]:
    """The file the command writes."""
    return [args.out / "gain.png"]


def run(args: argparse.Namespace) -> int:
    """Take the step, print the chosen viewpoint and draw the step."""
    from covmap.experiments import planning_step
    from covmap.plot import plot_planning_step

    world = _options.world_building(args).world
    step = planning_step.run(world, scans=args.scans, seed=args.seed, alpha=args.alpha)
    print(f"world {args.world}")
    print(planning_step.report(step))
    path = plot_planning_step(step, outputs(args)[0])
    print(f"wrote {path}")
    return 0
