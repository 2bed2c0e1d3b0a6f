"""Buildings to explore, by name, and the fixed split of the benchmark.

A *building reference* is a string naming a :class:`~covmap.Building`
(:func:`building`):

- a built-in world: ``"corridor"``, ``"office"``, ``"partial"``;
- a generated building: ``"generated:SEED"`` (the default area, 200
  square metres) or ``"generated:SEED:AREA"`` (``AREA`` square metres);
- a world file (a name with a suffix: ``.map``, ``.json``/``.geojson``,
  ``.yaml``/``.yml``; ``.pgm``/``.png`` with ``image_resolution``), its
  rooms found by the rule for plans (:meth:`covmap.Building.from_world`).

The split
---------
The strategies' constants were chosen on the built-in ``corridor`` and
``office``. Every claim about exploration is made on buildings that were
not looked at while tuning:

- **development** (free to look at, to tune and fit on): generated
  buildings of the seeds :data:`DEVELOPMENT_SEEDS`, and the built-in
  worlds :data:`DEVELOPMENT_PLANS`;
- **test** (only ever reported, never tuned on): generated buildings of
  the seeds :data:`TEST_SEEDS`, and the real plans :data:`TEST_PLANS`
  (read from ``../shared/data/worlds`` beside the checkout, or another
  folder given).

:func:`building_set` builds the named sets the benchmark runs on:
``"default"`` (a newcomer's few minutes: :data:`DEFAULT_COUNT` small
development buildings), ``"development"`` and ``"test"`` (``count``
generated buildings each, their areas cycling through :data:`SET_AREAS_M2`,
then the set's plans).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

from covmap._errors import FileIOError, InvalidParameterError, InvalidTypeError, UnknownWorldError
from covmap._native import Building, World

if TYPE_CHECKING:
    from collections.abc import Sequence

__all__ = [
    "DEFAULT_COUNT",
    "DEFAULT_PLANS_DIR",
    "DEVELOPMENT_PLANS",
    "DEVELOPMENT_SEEDS",
    "MAX_REFERENCES",
    "SETS",
    "SET_AREAS_M2",
    "SMALL_AREA_M2",
    "TEST_PLANS",
    "TEST_SEEDS",
    "building",
    "building_set",
    "buildings",
    "spec_world",
    "split_of",
]

DEVELOPMENT_SEEDS = range(0, 1000)
"""The seeds of the development buildings: look at them, tune on them."""

TEST_SEEDS = range(1000, 2000)
"""The seeds of the test buildings: report them, never tune on them."""

DEVELOPMENT_PLANS = ("corridor", "office")
"""The built-in worlds the strategies' constants were chosen on: development."""

TEST_PLANS: dict[str, dict[str, Any]] = {
    "AMROffice.map": {},
    "stata_basement.yaml": {},
    "willow-full.pgm": {"resolution": 0.1},
}
"""The real plans of the test set, by file name, with the arguments of
:meth:`covmap.Building.from_file` each needs (``../shared/data/README.md``:
Willow's image is 0.1 m a pixel)."""

DEFAULT_PLANS_DIR = Path("..", "shared", "data", "worlds")
"""Where :data:`TEST_PLANS` are read from unless told otherwise: the
shared data folder beside the checkout."""

SMALL_AREA_M2 = 120.0
"""The area of the default set's buildings, square metres: a corridor and
some six rooms, a run of every strategy in seconds."""

DEFAULT_COUNT = 4
"""How many buildings the default set holds."""

SET_AREAS_M2 = (120.0, 250.0, 550.0)
"""The areas the generated buildings of a set cycle through, square
metres: small, medium, and the size of the AMROffice plan."""

SETS = ("default", "development", "test")
"""The names of the building sets."""

MAX_REFERENCES = 100_000
"""The most building references :func:`buildings` takes."""

GENERATED = "generated"
"""The prefix of a generated building's reference."""


def _generated(reference: str) -> Building:
    parts = reference.split(":")
    if len(parts) not in (2, 3) or parts[0] != GENERATED:
        raise UnknownWorldError(f"a generated building is named generated:SEED or generated:SEED:AREA, got {reference!r}")
    try:
        seed = int(parts[1])
        area = float(parts[2]) if len(parts) == 3 else None
    except ValueError:
        raise InvalidParameterError(
            f"a generated building is named generated:SEED or generated:SEED:AREA (SEED an integer, AREA a number), "
            f"got {reference!r}"
        ) from None
    if not 0 <= seed <= 2**64 - 1:
        raise InvalidParameterError(f"invalid parameter `seed` = {seed}: expected 0 to 2**64 - 1 in {reference!r}")
    return Building.generate(seed) if area is None else Building.generate(seed, area_m2=area)


def building(reference: str | Building | World, *, image_resolution: float | None = None) -> Building:
    """The building ``reference`` names (see the module's documentation);
    a :class:`~covmap.Building` is returned as it is, a
    :class:`~covmap.World` becomes one (:meth:`~covmap.Building.from_world`).
    A name that is neither a built-in world, nor ``generated:...``, nor a
    file name raises :class:`~covmap.UnknownWorldError`; a file that cannot
    be read :class:`~covmap.FileIOError`; a generator parameter out of range
    :class:`~covmap.InvalidParameterError`. ``image_resolution``: metres a
    pixel of a ``.pgm``/``.png`` file."""
    if isinstance(reference, Building):
        return reference
    if isinstance(reference, World):
        return Building.from_world(reference)
    if not isinstance(reference, str):
        raise InvalidTypeError(
            f"a building is a Building, a World or a name (built-in, generated:SEED[:AREA], a file), "
            f"got {type(reference).__name__}"
        )
    if reference.startswith(GENERATED + ":"):
        return _generated(reference)
    if reference in World.builtin_names():
        return Building.builtin(reference)
    path = Path(reference)
    if not path.suffix:
        raise UnknownWorldError(
            f"no building named {reference!r}: expected a built-in world ({', '.join(World.builtin_names())}), "
            "generated:SEED[:AREA] or a world file"
        )
    options = dict(TEST_PLANS.get(path.name, {}))
    if image_resolution is not None:
        options["resolution"] = image_resolution
    return Building.from_file(path, **options)


def spec_world(value: Any) -> tuple[World, str, Building | None]:
    """A sweep spec's world (:func:`covmap.sweep`), its label and its
    building (whose rooms a run is judged on): a ``World`` is its own, with
    its ``repr`` and no rooms; a ``Building`` gives its world and name; a
    name (:func:`building`) its building, labelled by the name."""
    if isinstance(value, World):
        return value, repr(value), None
    if isinstance(value, Building):
        return value.world, value.name, value
    if isinstance(value, str):
        found = building(value)
        return found.world, value, found
    raise InvalidTypeError(f"world must be a World, a Building or a building's name, got {type(value).__name__}")


def split_of(name: str) -> str:
    """Which part of the split a building belongs to, by its name
    (:attr:`covmap.Building.name`): ``"development"``, ``"test"``, or
    ``"-"`` (neither: another seed, another file)."""
    if not isinstance(name, str):
        raise InvalidTypeError(f"a building's name is a str, got {type(name).__name__}")
    if name.startswith(GENERATED + ":"):
        try:
            seed = int(name.split(":")[1])
        except (IndexError, ValueError):
            return "-"
        if seed in DEVELOPMENT_SEEDS:
            return "development"
        if seed in TEST_SEEDS:
            return "test"
        return "-"
    if name in DEVELOPMENT_PLANS:
        return "development"
    if name in TEST_PLANS:
        return "test"
    return "-"


def building_set(
    name: str, *, count: int | None = None, plans: bool = True, plans_dir: str | os.PathLike[str] | None = None
) -> list[Building]:
    """The buildings of set ``name`` (:data:`SETS`):

    - ``"default"``: ``count`` (default :data:`DEFAULT_COUNT`) development
      buildings of :data:`SMALL_AREA_M2`, seeds 0, 1, ...;
    - ``"development"``: ``count`` (default 12) development buildings, seeds
      0, 1, ..., their areas cycling through :data:`SET_AREAS_M2`, then (with
      ``plans``) :data:`DEVELOPMENT_PLANS`;
    - ``"test"``: ``count`` (default 12) test buildings, seeds 1000, 1001, ...,
      areas as above, then (with ``plans``) :data:`TEST_PLANS` from
      ``plans_dir`` (default :data:`DEFAULT_PLANS_DIR`; a missing plan raises
      :class:`~covmap.FileIOError` naming it).

    An unknown set raises :class:`~covmap.UnknownWorldError`, a count below
    1 or beyond the split's seeds :class:`~covmap.InvalidParameterError`:
    a split without buildings is refused."""
    if not isinstance(name, str):
        raise InvalidTypeError(f"a building set is named by a str ({', '.join(SETS)}), got {type(name).__name__}")
    if name not in SETS:
        raise UnknownWorldError(f"no building set named {name!r}; available: {', '.join(SETS)}")
    if not isinstance(plans, bool):
        raise InvalidTypeError(f"plans must be True or False, got {type(plans).__name__}")
    if plans_dir is not None and not isinstance(plans_dir, (str, os.PathLike)):
        raise InvalidTypeError(f"plans_dir must be a path, got {type(plans_dir).__name__}")
    default_count = DEFAULT_COUNT if name == "default" else 12
    count = default_count if count is None else count
    seeds = TEST_SEEDS if name == "test" else DEVELOPMENT_SEEDS
    if isinstance(count, bool) or not isinstance(count, int) or not 1 <= count <= len(seeds):
        raise InvalidParameterError(
            f"invalid parameter `count` = {count!r}: expected from 1 to {len(seeds)} buildings of the {name} set"
        )
    if name == "default":
        return [Building.generate(seeds[i], area_m2=SMALL_AREA_M2) for i in range(count)]
    found = [Building.generate(seeds[i], area_m2=SET_AREAS_M2[i % len(SET_AREAS_M2)]) for i in range(count)]
    if not plans:
        return found
    if name == "development":
        return found + [Building.builtin(p) for p in DEVELOPMENT_PLANS]
    folder = Path(DEFAULT_PLANS_DIR if plans_dir is None else plans_dir)
    for plan, options in TEST_PLANS.items():
        path = folder / plan
        if not path.is_file():
            raise FileIOError(f"{path}: the test plan {plan} is missing (plans are read from {folder})")
        found.append(Building.from_file(path, **options))
    return found


def buildings(references: Sequence[str], **options: Any) -> list[Building]:
    """The buildings of ``references``, each a set name (its buildings,
    ``options`` passed to :func:`building_set`) or a building reference
    (:func:`building`); at most :data:`MAX_REFERENCES` of them."""
    if isinstance(references, str) or not hasattr(references, "__len__"):
        raise InvalidTypeError(f"references must be a list of names, got {type(references).__name__}")
    try:
        too_many = len(references) > MAX_REFERENCES
    except OverflowError:
        too_many = True
    if too_many:
        raise InvalidParameterError(f"too many references: expected at most {MAX_REFERENCES}")
    found: list[Building] = []
    for reference in references:
        if not isinstance(reference, (str, Building, World)):
            raise InvalidTypeError(f"a building reference is a name, got {type(reference).__name__}")
        if reference in SETS:
            found.extend(building_set(reference, **options))
        else:
            found.append(building(reference))
    return found
