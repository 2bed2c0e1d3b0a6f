"""The ``covmap`` command line (also ``python -m covmap``)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from covmap._native import __version__

if TYPE_CHECKING:
    from collections.abc import Sequence


def _positive_int(text: str) -> int:
    value = int(text)
    if value <= 0:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text}")
    return value


def parser() -> argparse.ArgumentParser:
    """The argument parser, one subcommand per experiment."""
    p = argparse.ArgumentParser(
        prog="covmap", description="Coverage maps (Stachniss and Burgard, 2003)."
    )
    p.add_argument("--version", action="version", version=f"covmap {__version__}")
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND")
    fig1 = sub.add_parser(
        "fig1",
        help="reproduce Fig. 1: a partly covered cell, coverage map vs occupancy grid",
        description=(
            "A wall covering the far 20, 50 and 80 %% of one cell, seen by laser beams "
            "from varied positions: prints the coverage map's ML and mean coverage and "
            "the occupancy probability of the cell, writes fig1.png, and exits non-zero "
            "unless the ML coverage lies within one bin of the truth and p(occ) > 0.9."
        ),
    )
    fig1.add_argument(
        "--out", type=Path, default=Path("covmap-out/fig1"), help="output directory"
    )
    fig1.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    fig1.add_argument(
        "--readings",
        type=_positive_int,
        default=200,
        help="readings per fraction (default 200)",
    )
    return p


def _fig1(args: argparse.Namespace) -> int:
    from covmap import fig1

    runs = fig1.run_all(seed=args.seed, readings=args.readings)
    print(f"Fig. 1, laser, {args.readings} readings per fraction, seed {args.seed}")
    print(fig1.table(runs))
    path = args.out / "fig1.png"
    fig1.plot(runs, path)
    print(f"wrote {path}")
    ok = all(r.ml_ok and r.occupancy_ok for r in runs)
    print("PASS" if ok else "FAIL: the expected outcome did not hold")
    return 0 if ok else 1


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    args = parser().parse_args(argv)
    if args.command == "fig1":
        return _fig1(args)
    raise AssertionError(f"unhandled command {args.command}")


if __name__ == "__main__":
    sys.exit(main())
