"""The ``covmap`` command line (also ``python -m covmap``)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from covmap._errors import CovmapError
from covmap._native import Grid, World, __version__, run_fig3

if TYPE_CHECKING:
    from collections.abc import Sequence


_MAX_SEED = 2**64 - 1
"""The largest seed: seeds are unsigned 64-bit integers."""

_MAX_COUNT = 1_000_000
"""The most readings or scans a command takes (more would run for hours)."""

_MIN_LENGTH_M = 1e-6
"""The smallest cell or pixel size, metres: the finest grid covmap builds."""

_MAX_LENGTH_M = 1000.0
"""The largest cell or pixel size, metres: a kilometre is beyond any robot's
world, and larger values overflow the areas computed from them or exhaust the
memory building the world."""

_MAX_WALL_THICKNESS_M = 100.0
"""The thickest wall an ARIA map's segments may be drawn as, metres (the
library's limit)."""


def _integer(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected an integer, got {text}") from None


def _positive_int(text: str) -> int:
    value = _integer(text)
    if not 0 < value <= _MAX_COUNT:
        raise argparse.ArgumentTypeError(f"expected an integer from 1 to {_MAX_COUNT}, got {text}")
    return value


def _number(text: str) -> float:
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text}") from None


def _length(text: str) -> float:
    """A cell or pixel size, metres."""
    value = _number(text)
    if not _MIN_LENGTH_M <= value <= _MAX_LENGTH_M:
        raise argparse.ArgumentTypeError(
            f"expected a length in metres from {_MIN_LENGTH_M:g} to {_MAX_LENGTH_M:g}, got {text}"
        )
    return value


def _wall_thickness(text: str) -> float:
    value = _number(text)
    if not 0.0 < value <= _MAX_WALL_THICKNESS_M:
        raise argparse.ArgumentTypeError(
            f"expected a thickness in metres, more than 0 and at most {_MAX_WALL_THICKNESS_M:g}, got {text}"
        )
    return value


def _weight(text: str) -> float:
    value = _number(text)
    if not 0.0 <= value <= 1.0:
        raise argparse.ArgumentTypeError(f"expected a weight in [0, 1], got {text}")
    return value


def _seed(text: str) -> int:
    value = _integer(text)
    if not 0 <= value <= _MAX_SEED:
        raise argparse.ArgumentTypeError(f"expected a seed from 0 to 2**64 - 1, got {text}")
    return value


def _add_out(command: argparse.ArgumentParser, name: str) -> None:
    """The ``--out`` option of subcommand ``name``, default ``covmap-out/<name>``."""
    command.add_argument(
        "--out",
        type=Path,
        default=Path("covmap-out", name),
        help=f"output directory (default covmap-out/{name})",
    )


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
            "A wall covering the far 20, 50 and 80 % of one cell, seen by laser beams "
            "from varied positions: prints the coverage map's ML and mean coverage and "
            "the occupancy probability of the cell, writes fig1.png, and exits non-zero "
            "unless the ML coverage lies within one bin of the truth and p(occ) > 0.9."
        ),
    )
    _add_out(fig1, "fig1")
    fig1.add_argument("--seed", type=_seed, default=0, help="random seed, 0 to 2**64 - 1 (default 0)")
    fig1.add_argument(
        "--readings",
        type=_positive_int,
        default=200,
        help="readings per fraction, at most 1000000 (default 200)",
    )

    world = sub.add_parser(
        "world",
        help="draw a world and its exact ground-truth coverage",
        description=(
            "Draw a world's obstacles (NAME-world.png) and its exact coverage on a grid "
            "over its bounds (NAME-coverage.png); print its bounds and obstacle area. "
            "NAME is a built-in world (corridor, office, partial) or a world file "
            "(.json/.geojson, .map, .yaml/.yml; .pgm/.png with --image-resolution)."
        ),
    )
    world.add_argument("name", metavar="NAME", help="built-in world or world file")
    _add_out(world, "world")
    world.add_argument(
        "--resolution",
        type=_length,
        default=0.05,
        help="cell size of the coverage grid, metres, from 1e-06 to 1000 (default 0.05)",
    )
    world.add_argument(
        "--wall-thickness",
        type=_wall_thickness,
        default=0.1,
        help="thickness of the walls of an ARIA .map file, metres, at most 100 (default 0.1)",
    )
    world.add_argument(
        "--image-resolution",
        type=_length,
        help="metres per pixel of a .pgm/.png world, from 1e-06 to 1000",
    )

    fig3 = sub.add_parser(
        "fig3",
        help="reproduce Fig. 3: a corridor mapped with simulated sonars",
        description=(
            "Drive 24 simulated sonars along a seeded path through the built-in corridor, "
            "build a coverage map and an occupancy grid from the same readings, print their "
            "mean absolute errors against the exact ground truth and the log-likelihood of "
            "the truth, and write fig3-truth.png, fig3-ml.png and fig3-occupancy.png."
        ),
    )
    _add_out(fig3, "fig3")
    fig3.add_argument("--seed", type=_seed, default=0, help="random seed, 0 to 2**64 - 1 (default 0)")

    gain = sub.add_parser(
        "gain",
        help="expected information gain and the next viewpoint after a few sonar scans",
        description=(
            "Scan a built-in world a few times with 24 simulated sonars from a free pose near "
            "one end of its main passage, integrate the scans into a coverage map, let the "
            "planner choose the next viewpoint, print it, and write gain.png: the ML map and "
            "the expected gain of every candidate with the chosen viewpoint and its path."
        ),
    )
    gain.add_argument("--world", default="corridor", help="built-in world (default corridor)")
    _add_out(gain, "gain")
    gain.add_argument(
        "--scans", type=_positive_int, default=3, help="sonar scans, at most 1000000 (default 3)"
    )
    gain.add_argument("--seed", type=_seed, default=0, help="random seed, 0 to 2**64 - 1 (default 0)")
    gain.add_argument(
        "--alpha",
        type=_weight,
        default=0.5,
        help="weight of gain against travel cost in [0, 1] (default 0.5)",
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


def _load_world(args: argparse.Namespace) -> tuple[World, str]:
    """The world NAME names, and a name for its files."""
    if args.name in World.builtin_names():
        return World.builtin(args.name), args.name
    path = Path(args.name)
    if not path.suffix:
        # Not a file name: let the built-in lookup say which names exist.
        return World.builtin(args.name), args.name
    world = World.from_file(
        path, wall_thickness_m=args.wall_thickness, resolution=args.image_resolution
    )
    return world, path.stem


def _world(args: argparse.Namespace) -> int:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from covmap.plot import plot_map, plot_world, save_figure

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
    scale = 8.0 / max(x1 - x0, y1 - y0)
    size = (max(4.0, (x1 - x0) * scale + 1.5), max(3.0, (y1 - y0) * scale + 1.0))
    for kind in ("world", "coverage"):
        fig, ax = plt.subplots(figsize=size, layout="constrained")
        try:
            if kind == "world":
                plot_world(world, ax)
                ax.set_title(f"{name}: {len(world)} obstacles (glass light blue)")
            else:
                plot_map(coverage, grid, ax, title=f"{name}: exact coverage, {grid.resolution:g} m cells", colorbar=True)
            path = save_figure(fig, args.out / f"{name}-{kind}.png")
        finally:
            plt.close(fig)
        print(f"wrote {path}")
    return 0


def _fig3(args: argparse.Namespace) -> int:
    from covmap import fig3

    result = run_fig3(args.seed)
    print(fig3.table(result, args.seed))
    for path in fig3.plot(result, args.out):
        print(f"wrote {path}")
    return 0


def _gain(args: argparse.Namespace) -> int:
    from covmap import explore

    world = World.builtin(args.world)
    step = explore.run(world, scans=args.scans, seed=args.seed, alpha=args.alpha)
    print(f"world {args.world}")
    print(explore.report(step))
    path = explore.plot(step, args.out / "gain.png")
    print(f"wrote {path}")
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    args = parser().parse_args(argv)
    try:
        if args.command == "fig1":
            return _fig1(args)
        if args.command == "world":
            return _world(args)
        if args.command == "fig3":
            return _fig3(args)
        if args.command == "gain":
            return _gain(args)
    except (CovmapError, OSError) as e:
        # Bad names, bad files: say what is wrong, without a traceback.
        print(f"covmap {args.command}: error: {e}", file=sys.stderr)
        return 2 if isinstance(e, ValueError) else 1
    raise AssertionError(f"unhandled command {args.command}")


if __name__ == "__main__":
    sys.exit(main())
