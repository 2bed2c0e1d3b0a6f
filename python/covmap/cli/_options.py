"""What the commands' options accept: argument types that check their range,
and the options several commands share."""

from __future__ import annotations

import argparse
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, TypeVar

if TYPE_CHECKING:
    from covmap._native import LaserModel, SonarModel

T = TypeVar("T", int, float)

MAX_SEED = 2**64 - 1
"""The largest seed: seeds are unsigned 64-bit integers."""

MAX_COUNT = 1_000_000
"""The most readings or scans a command takes (more would run for hours)."""

MIN_LENGTH_M = 1e-6
"""The smallest cell or pixel size, metres: the finest grid covmap builds."""

MAX_LENGTH_M = 1000.0
"""The largest cell or pixel size, metres: a kilometre is beyond any robot's
world, and larger values overflow the areas computed from them or exhaust the
memory building the world."""

MAX_WALL_THICKNESS_M = 100.0
"""The thickest wall an ARIA map's segments may be drawn as, metres (the
library's limit)."""


def _integer(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected an integer, got {text}") from None


def _number(text: str) -> float:
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text}") from None


def _within(parse: Callable[[str], T], valid: Callable[[T], bool], expected: str) -> Callable[[str], T]:
    """An argument type: the text read by ``parse``, refused unless ``valid``
    (a NaN fails every comparison, so a range check refuses it)."""

    def check(text: str) -> T:
        value = parse(text)
        if not valid(value):
            raise argparse.ArgumentTypeError(f"expected {expected}, got {text}")
        return value

    return check


positive_int = _within(_integer, lambda v: 0 < v <= MAX_COUNT, f"an integer from 1 to {MAX_COUNT}")
"""A count of readings or scans."""

length = _within(
    _number,
    lambda v: MIN_LENGTH_M <= v <= MAX_LENGTH_M,
    f"a length in metres from {MIN_LENGTH_M:g} to {MAX_LENGTH_M:g}",
)
"""A cell or pixel size, metres."""

wall_thickness = _within(
    _number,
    lambda v: 0.0 < v <= MAX_WALL_THICKNESS_M,
    f"a thickness in metres, more than 0 and at most {MAX_WALL_THICKNESS_M:g}",
)
"""The thickness of an ARIA map's walls, metres."""

weight = _within(_number, lambda v: 0.0 <= v <= 1.0, "a weight in [0, 1]")
"""A weight in ``[0, 1]``."""

seed = _within(_integer, lambda v: 0 <= v <= MAX_SEED, "a seed from 0 to 2**64 - 1")
"""A seed of the random generators."""

MAX_PATH_M = 1_000_000.0
"""The longest path an exploration may be given as its limit, metres."""

MAX_FRAMES = 1000
"""The most frames an animation may be asked for."""

path_limit = _within(
    _number, lambda v: 0.0 < v <= MAX_PATH_M, f"a distance in metres, more than 0 and at most {MAX_PATH_M:g}"
)
"""An exploration's limit on its path length, metres."""

distance = _within(
    _number, lambda v: 0.0 < v <= MAX_LENGTH_M, f"a distance in metres, more than 0 and at most {MAX_LENGTH_M:g}"
)
"""A distance, metres: a reach, a range."""

discount = distance
"""The range beyond which scan counting discounts a beam, metres."""

entropy = _within(_number, lambda v: 0.0 < v <= 10.0, "an entropy in nats, more than 0 and at most 10")
"""The entropy below which a cell is certain, nats."""


unit = _within(_number, lambda v: 0.0 < v <= 1e6 and v == v, "metres per unit, more than 0 and at most 1e6")
"""Metres per length unit of a file (0.001 for millimetres)."""

reading_bound = _within(
    _number, lambda v: 0.0 <= v <= MAX_LENGTH_M, f"a distance in metres from 0 to {MAX_LENGTH_M:g}"
)
"""The shortest valid reading, metres."""

reading = _within(_number, lambda v: abs(v) <= 1e300, "a finite number")
"""A reading as a file writes it."""

MAX_BEARINGS = 4096
"""The most bearings a sonar log's description may list."""


def angle_unit(text: str) -> float:
    """Radians per angle unit: ``rad``, ``deg``, a number (radians), or a
    number followed by ``deg`` (``0.1deg``: tenths of a degree)."""
    import math

    word = text.strip().lower()
    factor, scale = (word[:-3], math.pi / 180.0) if word.endswith("deg") else (word.removesuffix("rad"), 1.0)
    try:
        value = (float(factor) if factor else 1.0) * scale
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected rad, deg, a number of radians or a number of degrees with deg (0.1deg), got {text}"
        ) from None
    if not 0.0 < value <= 2.0 * math.pi:
        raise argparse.ArgumentTypeError(f"expected an angle unit of more than 0 and at most a turn, got {text}")
    return value


def bearings(text: str) -> list[float]:
    """Bearings in degrees: numbers separated by commas, or the path of a
    file of numbers (separated by commas or white space)."""
    source, path = text, Path(text)
    if path.is_file():
        try:
            with open(path, encoding="utf-8") as f:
                source = f.read(65536 + 1)
        except (OSError, UnicodeDecodeError) as e:
            raise argparse.ArgumentTypeError(f"{text}: cannot read the bearings: {e}") from None
        if len(source) > 65536:
            raise argparse.ArgumentTypeError(f"{text}: more than 64 KB is not a list of bearings")
    words = source.replace(",", " ").split()
    if not 1 <= len(words) <= MAX_BEARINGS:
        raise argparse.ArgumentTypeError(f"expected from 1 to {MAX_BEARINGS} bearings, got {len(words)} in {text[:80]}")
    values = []
    for w in words:
        try:
            v = float(w)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"expected degrees separated by commas or a file of them, got {w[:80]!r} in {text[:80]}"
            ) from None
        if not abs(v) <= 360.0:
            raise argparse.ArgumentTypeError(f"expected a bearing from -360 to 360 degrees, got {w[:80]}")
        values.append(v)
    return values


def start_pose(text: str) -> tuple[float, float, float]:
    """A start ``X,Y`` or ``X,Y,THETA`` (metres, radians), finite."""
    import math

    parts = text.split(",")
    try:
        values = [float(p) for p in parts]
    except ValueError:
        values = []
    if len(values) not in (2, 3) or not all(math.isfinite(v) for v in values):
        raise argparse.ArgumentTypeError(f"expected X,Y or X,Y,THETA (finite numbers), got {text}")
    return (values[0], values[1], values[2] if len(values) == 3 else 0.0)


frame_count = _within(_integer, lambda v: 2 <= v <= MAX_FRAMES, f"an integer from 2 to {MAX_FRAMES}")
"""The most frames of an animation."""


def add_out(command: argparse.ArgumentParser, name: str) -> None:
    """The ``--out`` option of subcommand ``name``, default ``covmap-out/<name>``."""
    command.add_argument(
        "--out",
        type=Path,
        default=Path("covmap-out", name),
        help=f"output directory (default covmap-out/{name})",
    )


def add_world(command: argparse.ArgumentParser) -> None:
    """The ``--world`` option: a building, by name (a built-in world,
    ``generated:SEED[:AREA]``, a world file; see
    :func:`covmap.buildings.building`), default ``corridor``."""
    command.add_argument(
        "--world",
        default="corridor",
        help="built-in world (corridor, office, partial), generated building (generated:SEED or "
        "generated:SEED:AREA) or world file (.map, .json/.geojson, .yaml; .pgm/.png with "
        "--image-resolution) (default corridor)",
    )
    command.add_argument(
        "--image-resolution",
        type=length,
        metavar="M",
        help="metres per pixel of a .pgm/.png world file",
    )


def names(text: str) -> list[str]:
    """A list of names separated by commas."""
    found = [part.strip() for part in text.split(",") if part.strip()]
    if not found:
        raise argparse.ArgumentTypeError(f"expected names separated by commas, got {text!r}")
    return found


def add_buildings(command: argparse.ArgumentParser) -> None:
    """The ``--buildings`` option (a view over many buildings) and the
    ``--count`` and ``--plans`` of its sets."""
    from covmap.buildings import DEFAULT_PLANS_DIR

    command.add_argument(
        "--buildings",
        type=names,
        metavar="NAME,...",
        help="run over these buildings instead of --world: sets (default, development, test) or buildings "
        "(corridor, office, generated:SEED[:AREA], a world file), separated by commas",
    )
    command.add_argument(
        "--count",
        type=positive_int,
        help="generated buildings in each set named (default: 4 in default, 12 in development and test)",
    )
    command.add_argument(
        "--plans",
        default=str(DEFAULT_PLANS_DIR),
        metavar="DIR",
        help=f"where the test set's real plans are read from (default {DEFAULT_PLANS_DIR})",
    )


def chosen_buildings(args: argparse.Namespace) -> list[Any]:
    """The buildings of :func:`add_buildings`' options (``--buildings``
    given)."""
    from covmap.buildings import buildings

    return buildings(args.buildings, count=args.count, plans_dir=args.plans)


def world_building(args: argparse.Namespace) -> Any:
    """The building ``--world`` names (:func:`covmap.buildings.building`)."""
    from covmap.buildings import building

    return building(args.world, image_resolution=args.image_resolution)


def add_seed(command: argparse.ArgumentParser) -> None:
    """The ``--seed`` option, default 0."""
    command.add_argument("--seed", type=seed, default=0, help="random seed, 0 to 2**64 - 1 (default 0)")


def add_run_limits(command: argparse.ArgumentParser, *, max_path_m: float | None = None) -> None:
    """The ``--max-steps`` and ``--max-path-m`` options of an exploration
    (default: the library's limits, or ``max_path_m`` where the command has
    its own)."""
    from covmap._native import _EXPLORE_DEFAULTS as defaults

    max_path_m = defaults["max_path_m"] if max_path_m is None else max_path_m
    command.add_argument(
        "--max-steps",
        type=positive_int,
        help=f"stop a run after this many steps, at most {MAX_COUNT} (default {defaults['max_steps']})",
    )
    command.add_argument(
        "--max-path-m",
        type=path_limit,
        help=f"stop a run after driving this far, metres (default {max_path_m:g})",
    )


def run_limits(args: argparse.Namespace) -> dict[str, Any]:
    """The limits of :func:`add_run_limits` that were given, as keywords of
    :func:`covmap.explore`."""
    limits = {"max_steps": args.max_steps, "max_path_m": args.max_path_m}
    return {name: value for name, value in limits.items() if value is not None}


def add_dask(command: argparse.ArgumentParser, *, local: bool = True) -> None:
    """The ``--dask ADDRESS`` option (and, with ``local``, ``--dask-local
    WORKERS``, excluding it): where a sweep's runs go; neither: the local
    cores."""
    group = command.add_mutually_exclusive_group()
    group.add_argument(
        "--dask",
        metavar="ADDRESS",
        help="run on the Dask scheduler at ADDRESS (tcp://host:8786; needs covmap[dask]) "
        "instead of this machine's cores",
    )
    if local:
        group.add_argument(
            "--dask-local",
            type=positive_int,
            metavar="WORKERS",
            help="run on a Dask cluster of WORKERS worker processes started on this machine (needs covmap[dask])",
        )


def check_outputs(paths: list[Path]) -> None:
    """Refuse, before a command computes or writes anything, every file it
    would write that it may not: a directory, a device, a FIFO, a socket or
    a symlink where the file would go (``FileIOError``; covmap replaces only
    regular files), so that no command writes some of its files and then
    stops."""
    from covmap._native import check_write_target

    for path in paths:
        check_write_target(path)


@contextmanager
def executor(args: argparse.Namespace) -> Iterator[Any]:
    """The executor :func:`add_dask`'s options ask for (``None``: the local
    cores), closed when the block ends."""
    from covmap._executors import dask_client

    if args.dask is not None:
        with dask_client(args.dask) as client:
            yield client
    elif getattr(args, "dask_local", None) is not None:
        with dask_client(workers=args.dask_local) as client:
            yield client
    else:
        yield None


def load_model(path: str) -> SonarModel | LaserModel:
    """The model a ``covmap learn`` JSON file holds: ``{"sensor": "sonar" |
    "laser", "model": {...}}``."""
    import json

    from covmap._errors import InvalidValueError, quoted
    from covmap._native import LaserModel, SonarModel
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
