"""``covmap fig1``: the paper's Fig. 1, a partly covered cell."""

from __future__ import annotations

from typing import TYPE_CHECKING

from covmap.cli import _options

if TYPE_CHECKING:
    import argparse
    from pathlib import Path

NAME = "fig1"
"""The command's name: ``covmap fig1``."""

HELP = "reproduce Fig. 1: a partly covered cell, coverage map vs occupancy grid"
"""The command's line in ``covmap --help``."""

DESCRIPTION = (
    "A wall covering the far 20, 50 and 80 % of one cell, seen by laser beams "
    "from varied positions: prints the coverage map's ML and mean coverage and "
    "the occupancy probability of the cell, writes fig1.png, and exits non-zero "
    "unless the ML coverage lies within one bin of the truth and p(occ) > 0.9."
)
"""What ``covmap fig1 --help`` says the command does."""


def add_arguments(command: argparse.ArgumentParser) -> None:
    """The command's arguments."""
    _options.add_out(command, NAME)
    _options.add_seed(command)
    command.add_argument(
        "--readings",
        type=_options.positive_int,
        default=200,
        help="readings per fraction, at most 1000000 (default 200)",
    )


def outputs(args: argparse.Namespace) -> list[Path]:
    """The file the command writes."""
    return [args.out / "fig1.png"]


def run(args: argparse.Namespace) -> int:
    """Run the experiment, print its table and write its figure; 1 unless
    the expected outcome held."""
    from covmap.experiments import fig1
    from covmap.plot import plot_fig1

    runs = fig1.run_all(seed=args.seed, readings=args.readings)
    print(f"Fig. 1, laser, {args.readings} readings per fraction, seed {args.seed}")
    print(fig1.table(runs))
    path = plot_fig1(runs, outputs(args)[0])
    print(f"wrote {path}")
    ok = all(r.ml_ok and r.occupancy_ok for r in runs)
    print("PASS" if ok else "FAIL: the expected outcome did not hold")
    return 0 if ok else 1
