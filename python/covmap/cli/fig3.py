"""``covmap fig3``: the paper's Fig. 3, a corridor mapped with simulated sonars."""

from __future__ import annotations

from typing import TYPE_CHECKING

from covmap._native import run_fig3
from covmap.cli import _options

if TYPE_CHECKING:
    import argparse
    from pathlib import Path

NAME = "fig3"
"""The command's name: ``covmap fig3``."""

HELP = "reproduce Fig. 3: a corridor mapped with simulated sonars"
"""The command's line in ``covmap --help``."""

DESCRIPTION = (
    "Drive 24 simulated sonars along a seeded path through the built-in corridor, "
    "build a coverage map and an occupancy grid from the same readings, print their "
    "mean absolute errors against the exact ground truth and the log-likelihood of "
    "the truth, and write fig3-truth.png, fig3-ml.png and fig3-occupancy.png."
)
"""What ``covmap fig3 --help`` says the command does."""


def add_arguments(command: argparse.ArgumentParser) -> None:
    """The command's arguments."""
    _options.add_out(command, NAME)
    _options.add_seed(command)


def outputs(args: argparse.Namespace) -> list[Path]:
    """The files the command writes."""
    from covmap.plot.figures import fig3_paths

    return fig3_paths(args.out)


def run(args: argparse.Namespace) -> int:
    """Run the experiment, print its figures and draw its maps."""
    from covmap.experiments import fig3
    from covmap.plot import plot_fig3

    result = run_fig3(args.seed)
    print(fig3.table(result, args.seed))
    for path in plot_fig3(result, args.out):
        print(f"wrote {path}")
    return 0
