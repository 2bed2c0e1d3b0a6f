"""``covmap view``: a saved posterior (or a map_server pair) drawn, and
recorded for the Rerun viewer."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from covmap.cli import _options

if TYPE_CHECKING:
    import argparse

NAME = "view"
"""The command's name: ``covmap view``."""

HELP = "draw a saved coverage map (.npz) or a map_server pair (.yaml)"
"""The command's line in ``covmap --help``."""

DESCRIPTION = (
    "Draw a coverage map saved by CoverageMap.save or covmap map (FILE.npz: its maximum-likelihood "
    "coverage, mean and entropy, unknown cells in their own colour, as covmap map draws them) or a "
    "map_server pair (FILE.yaml with its image: the world it describes, unknown pixels as obstacles) "
    "into OUT/STEM.png; print the map's size and how much of it is known. --record FILE.rrd also "
    "writes the posterior's layers as a recording for the Rerun viewer (needs covmap[rerun]; open it "
    "with: rerun FILE.rrd)."
)
"""What ``covmap view --help`` says the command does."""


def add_arguments(command: argparse.ArgumentParser) -> None:
    """The command's arguments."""
    command.add_argument("file", metavar="FILE", type=Path, help="a saved coverage map (.npz) or a map_server YAML")
    _options.add_out(command, NAME)
    command.add_argument(
        "--record",
        type=Path,
        metavar="FILE.rrd",
        help="also write a recording for the Rerun viewer (a .npz only; needs covmap[rerun])",
    )


def outputs(args: argparse.Namespace) -> list[Path]:
    """The files the command writes: the picture, the recording."""
    return [args.out / f"{args.file.stem}.png", *([args.record] if args.record is not None else [])]


def run(args: argparse.Namespace) -> int:
    """Read the file, draw it, print its summary."""
    from covmap._errors import InvalidParameterError
    from covmap._native import CoverageMap, World

    suffix = args.file.suffix.lower()
    if suffix not in (".npz", ".yaml", ".yml"):
        raise InvalidParameterError(f"{args.file}: expected a saved coverage map (.npz) or a map_server YAML (.yaml)")
    if args.record is not None:
        if suffix != ".npz":
            raise InvalidParameterError("--record writes a coverage map's layers: give a .npz")
        from covmap._record import _rerun

        _rerun()
    picture = outputs(args)[0]
    args.out.mkdir(parents=True, exist_ok=True)
    if suffix == ".npz":
        from covmap.plot.mapping import plot_posterior

        cmap = CoverageMap.load(args.file)
        rows, cols = cmap.grid.shape
        known = float(cmap.observed().mean()) if rows * cols else 0.0
        print(f"{args.file}: grid {rows} x {cols} cells (rows x columns) of {cmap.grid.resolution:g} m, {cmap.bins} bins")
        print(f"known        {100 * known:.1f} % of the cells")
        plot_posterior(cmap, picture)
        if args.record is not None:
            from covmap._record import record_map

            record_map(args.record, cmap)
    else:
        from covmap.plot.figures import _figure_file
        from covmap.plot.drawing import plot_world

        world = World.from_file(args.file)
        x0, y0, x1, y1 = world.bounds
        print(f"{args.file}: a world of {x1 - x0:.2f} m x {y1 - y0:.2f} m, {len(world.polygons)} obstacles")
        with _figure_file(picture, figsize=(8.0, max(2.5, 8.0 * (y1 - y0) / max(x1 - x0, 1e-9)))) as (_, ax):
            plot_world(world, ax)
    for path in outputs(args):
        print(f"wrote {path}")
    return 0
