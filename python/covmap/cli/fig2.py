"""``covmap fig2``: the paper's Fig. 2, the inverse sensor model."""

from __future__ import annotations

from typing import TYPE_CHECKING

from covmap._native import LaserModel, SonarModel
from covmap.cli import _options

if TYPE_CHECKING:
    import argparse
    from pathlib import Path

NAME = "fig2"
"""The command's name: ``covmap fig2``."""

HELP = "reproduce Fig. 2: the sensor model p(c = x | d) over distance and coverage"
"""The command's line in ``covmap --help``."""

DESCRIPTION = (
    "Draw the inverse sensor model p(c_l = x | d) over the cell distance d_l and the "
    "coverage x for one measured distance d, for the default sonar model and, with "
    "--model, a learned one (a JSON file of covmap learn) side by side; writes fig2.png."
)
"""What ``covmap fig2 --help`` says the command does."""


def add_arguments(command: argparse.ArgumentParser) -> None:
    """The command's arguments."""
    _options.add_out(command, NAME)
    command.add_argument("--model", help="a learned model's JSON file (from covmap learn)")
    command.add_argument(
        "--distance",
        type=_options.distance,
        default=1.0,
        help="the measured distance d, metres (default 1.0)",
    )


def outputs(args: argparse.Namespace) -> list[Path]:
    """The file the command writes."""
    return [args.out / "fig2.png"]


def run(args: argparse.Namespace) -> int:
    """Draw the figure."""
    from covmap.plot.sensor_model import plot_fig2

    models: list[tuple[str, SonarModel | LaserModel]] = []
    if args.model is not None:
        learned = _options.load_model(args.model)
        default = type(learned)()
        models = [("default", default), ("learned", learned)]
    else:
        models = [("default", SonarModel())]
    path = plot_fig2(models, args.distance, outputs(args)[0])
    print(f"wrote {path}")
    return 0
