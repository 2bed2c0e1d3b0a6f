"""Shared fixtures: a small grid, the default models, random scans, the
real worlds of the shared data folder. Tests write only into temporary
directories they make: hypothesis keeps its files (examples, caches) in
one made for the session, not in the folder the tests run from."""

from __future__ import annotations

import atexit
import os
import shutil
import tempfile
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any, NoReturn

import numpy as np
import pytest

import covmap

try:
    from hypothesis import configuration as _hypothesis_configuration
    from hypothesis import settings as _hypothesis_settings
except ImportError:  # the property tests skip themselves
    pass
else:
    _HYPOTHESIS_HOME = tempfile.mkdtemp(prefix="covmap-hypothesis-")
    atexit.register(shutil.rmtree, _HYPOTHESIS_HOME, ignore_errors=True)
    _hypothesis_configuration.set_hypothesis_home_dir(_HYPOTHESIS_HOME)
    _hypothesis_settings.register_profile("covmap", database=None)
    _hypothesis_settings.load_profile("covmap")

Scan = tuple[tuple[float, float, float], np.ndarray, np.ndarray]


@pytest.fixture
def grid() -> covmap.Grid:
    """3 m x 2 m at 5 cm: 40 rows (y) by 60 columns (x)."""
    return covmap.Grid(origin=(0.0, 0.0), resolution=0.05, shape=(40, 60))


@pytest.fixture(params=["sonar", "laser"])
def model(request: pytest.FixtureRequest) -> Any:
    return covmap.SonarModel() if request.param == "sonar" else covmap.LaserModel()


def random_scans(grid: covmap.Grid, count: int, seed: int, beams: int = 24) -> Iterator[Scan]:
    """Scans from random poses inside ``grid``, some readings beyond any
    model's maximum range (no echo) and some zero."""
    rng = np.random.default_rng(seed)
    x0, y0, x1, y1 = grid.bounds
    for _ in range(count):
        pose = (
            float(rng.uniform(x0, x1 - 1e-9)),
            float(rng.uniform(y0, y1 - 1e-9)),
            float(rng.uniform(-np.pi, np.pi)),
        )
        ranges = rng.uniform(0.0, 3.0, beams)
        ranges[rng.random(beams) < 0.1] = 100.0
        ranges[rng.random(beams) < 0.05] = 0.0
        bearings = np.linspace(0.0, 2 * np.pi, beams, endpoint=False)
        yield pose, ranges, bearings


ScanSource = Callable[..., Iterator[Scan]]


@pytest.fixture
def scans() -> ScanSource:
    """``random_scans`` as a fixture (test modules do not import each other)."""
    return random_scans


@pytest.fixture
def scanned_map(grid: covmap.Grid, model: Any) -> covmap.CoverageMap:
    """A coverage map after 30 random scans."""
    cmap = covmap.CoverageMap(grid)
    for pose, ranges, bearings in random_scans(grid, 30, seed=7):
        cmap.integrate(pose, ranges, bearings, model)
    return cmap


SHARED_WORLDS = Path(__file__).resolve().parents[2].parent / "shared" / "data" / "worlds"
"""The real worlds, in the shared folder beside the repository (never copied into it)."""


def _missing(message: str) -> NoReturn:
    if os.environ.get("CI") == "true":
        pytest.fail(message + " (CI=true: the real-data tests must run)")
    pytest.skip(message + ": real-data test skipped (put the shared folder beside the repository)")


@pytest.fixture
def shared_world() -> Callable[[str], Path]:
    """``shared_world(name)``: the path of a real world file. Outside CI a
    missing folder or file skips the test with a message; under ``CI=true``
    it fails."""

    def find(name: str) -> Path:
        if not SHARED_WORLDS.is_dir():
            _missing(f"the shared data folder {SHARED_WORLDS} is absent")
        path = SHARED_WORLDS / name
        if not path.is_file():
            _missing(f"{path} is absent")
        return path

    return find


SHARED_DATA = SHARED_WORLDS.parent
"""The shared real-data folder (logs in ``carmen/`` and ``sonar-8ring/``)."""


@pytest.fixture
def shared_data() -> Callable[[str], Path]:
    """``shared_data("carmen/intel-corrected.log.gz")``: the path of a real
    data file, skipped (outside CI) or failed (``CI=true``) when absent."""

    def find(name: str) -> Path:
        path = SHARED_DATA / name
        if not path.is_file():
            _missing(f"{path} is absent")
        return path

    return find
