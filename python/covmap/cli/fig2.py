"""``covmap fig2``: the paper's Fig. 2, the inverse sensor model."""

from __future__ import annotations

import json
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


def load_model(path: str) -> SonarModel | LaserModel:
    """The model a ``covmap learn`` JSON file holds: ``{"sensor": "sonar" |
    "laser", "model": {...}}``."""
    from covmap._errors import InvalidValueError, quoted
    from covmap._read import read_small_file, too_deep

    data = read_small_file(path)
    deep = too_deep(data, "json")
    if deep is not None:
        raise InvalidValueError(f"{path}: not a covmap learn model file ({deep})")
    try:
        saved = json.loads(data)
        kind, parameters = saved["sensor"], saved["model"]
    except (ValueError, KeyError, TypeError) as e:
        raise InvalidValueError(f"{path}: not a covmap learn model file ({e})") from e
    except RecursionError:
        raise InvalidValueError(f"{path}: not a covmap learn model file (nested too deeply)") from None
    if kind not in ("sonar", "laser") or not isinstance(parameters, dict):
        raise InvalidValueError(f"{path}: sensor must be 'sonar' or 'laser', got {quoted(kind)}")
    cls = SonarModel if kind == "sonar" else LaserModel
    return cls.from_dict(parameters)


def outputs(args: argparse.Namespace) -> list[Path]:
    """The file the command writes."""
    return [args.out / "fig2.png"]


def run(args: argparse.Namespace) -> int:
    """Draw the figure."""
    from covmap.plot.sensor_model import plot_fig2

    models: list[tuple[str, SonarModel | LaserModel]] = []
    if args.model is not None:
        learned = load_model(args.model)
        default = type(learned)()
        models = [("default", default), ("learned", learned)]
    else:
        models = [("default", SonarModel())]
    path = plot_fig2(models, args.distance, outputs(args)[0])
    print(f"wrote {path}")
    return 0
