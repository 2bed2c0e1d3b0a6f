"""``covmap world``: a world and its exact ground-truth coverage."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import TYPE_CHECKING

from covmap._native import Grid, World
from covmap.cli import _options

if TYPE_CHECKING:
    import argparse

NAME = "world"
"""The command's name: ``covmap world``."""

HELP = "draw a world and its exact ground-truth coverage"
"""The command's line in ``covmap --help``."""

DESCRIPTION = (
    "Draw a world's obstacles (NAME-world.png) and its exact coverage on a grid "
    "over its bounds (NAME-coverage.png); print its bounds and obstacle area. "
    "NAME is a built-in world (corridor, office, partial), a generated building "
    "(generated:SEED or generated:SEED:AREA) or a world file "
    "(.json/.geojson, .map, .yaml/.yml; .pgm/.png with --image-resolution)."
)
"""What ``covmap world --help`` says the command does."""


def add_arguments(command: argparse.ArgumentParser) -> None:
    """The command's arguments."""
    command.add_argument("name", metavar="NAME", help="built-in world, generated:SEED[:AREA] or world file")
    _options.add_out(command, NAME)
    command.add_argument(
        "--resolution",
        type=_options.length,
        default=0.05,
        help="cell size of the coverage grid, metres, from 1e-06 to 1000 (default 0.05)",
    )
    command.add_argument(
        "--wall-thickness",
        type=_options.wall_thickness,
        default=None,
        help="thickness of the walls of an ARIA .map file, metres, at most 100 (default 0.1)",
    )
    command.add_argument(
        "--image-resolution",
        type=_options.length,
        help="metres per pixel of a .pgm/.png world, from 1e-06 to 1000",
    )


def _name(args: argparse.Namespace) -> str:
    """The name of the world's files: a built-in world's, a file's stem."""
    if args.name in World.builtin_names() or not Path(args.name).suffix:
        return str(args.name)
    return Path(args.name).stem


def outputs(args: argparse.Namespace) -> list[Path]:
    """The files the command writes: the obstacles and the coverage."""
    from covmap.plot.figures import world_paths

    return world_paths(_name(args), args.out)


def _load_world(args: argparse.Namespace) -> tuple[World, str]:
    """The world NAME names, and a name for its files."""
    if args.name in World.builtin_names():
        return World.builtin(args.name), args.name
    if args.name.startswith("generated:"):
        from covmap.buildings import building

        return building(args.name).world, args.name.replace(":", "-")
    path = Path(args.name)
    if not path.suffix:
        # Not a file name: let the built-in lookup say which names exist.
        return World.builtin(args.name), args.name
    world = World.from_file(
        path, wall_thickness_m=args.wall_thickness, resolution=args.image_resolution
    )
    return world, path.stem


def run(args: argparse.Namespace) -> int:
    """Print the world's bounds and obstacle area and draw it; 1 for a world
    without obstacles."""
    from covmap.plot import plot_world_and_coverage

    world, name = _load_world(args)
    if len(world) == 0:
        print(f"{name}: the world has no obstacles", file=sys.stderr)
        return 1
    x0, y0, x1, y1 = world.bounds
    grid = Grid.covering(world.bounds, resolution=args.resolution)
    coverage = world.coverage(grid)
    # A product, not ``**``: a float power raises OverflowError where a product gives inf.
    union_m2 = float(coverage.sum()) * grid.resolution * grid.resolution
    print(f"world {name}: {len(world)} polygons ({world.materials.count('glass')} glass)")
    print(f"bounds: x {x0:.3f} to {x1:.3f} m, y {y0:.3f} to {y1:.3f} m ({x1 - x0:.3f} x {y1 - y0:.3f} m)")
    print(
        f"obstacle area: {union_m2:.3f} m^2 (union, from the exact coverage at "
        f"{grid.resolution:g} m; polygons add up to {world.polygon_area_m2:.3f} m^2)"
    )
    print(f"coverage grid: {grid.rows} x {grid.cols} cells of {grid.resolution:g} m")
    for path in plot_world_and_coverage(world, grid, coverage, name, args.out):
        print(f"wrote {path}")
    return 0
