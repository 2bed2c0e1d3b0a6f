"""Bad input raises a specific error and leaves the map exactly as it was."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np
import pytest

import covmap

if TYPE_CHECKING:
    from conftest import ScanSource

POSE = (1.0, 1.0, 0.3)
R = np.array([1.0, 2.0, 0.5])
B = np.array([0.0, 1.0, 2.0])

# (name, pose, ranges, bearings, expected class, expected builtin base)
CASES: list[tuple[str, Any, Any, Any, type[Exception], type[Exception]]] = [
    ("nan range", POSE, np.array([1.0, math.nan, 0.5]), B, covmap.InvalidRangeError, ValueError),
    ("nan range last", POSE, np.array([1.0, 2.0, math.nan]), B, covmap.InvalidRangeError, ValueError),
    ("negative range", POSE, np.array([1.0, -0.1, 0.5]), B, covmap.InvalidRangeError, ValueError),
    ("infinite range", POSE, np.array([math.inf, 1.0, 0.5]), B, covmap.InvalidRangeError, ValueError),
    ("nan bearing", POSE, R, np.array([0.0, 1.0, math.nan]), covmap.InvalidBearingError, ValueError),
    ("inf bearing", POSE, R, np.array([math.inf, 1.0, 2.0]), covmap.InvalidBearingError, ValueError),
    ("nan pose", (math.nan, 1.0, 0.0), R, B, covmap.InvalidPoseError, ValueError),
    ("inf heading", (1.0, 1.0, math.inf), R, B, covmap.InvalidPoseError, ValueError),
    ("pose left of map", (-0.01, 1.0, 0.0), R, B, covmap.PoseOutsideMapError, ValueError),
    ("pose on upper edge", (3.0, 1.0, 0.0), R, B, covmap.PoseOutsideMapError, ValueError),
    ("pose above map", (1.0, 2.5, 0.0), R, B, covmap.PoseOutsideMapError, ValueError),
    ("short bearings", POSE, R, B[:2], covmap.LengthMismatchError, ValueError),
    ("int ranges", POSE, np.array([1, 2, 3]), B, covmap.ArrayDtypeError, TypeError),
    ("float32 bearings", POSE, R, B.astype(np.float32), covmap.ArrayDtypeError, TypeError),
    ("2-D ranges", POSE, R.reshape(3, 1), B, covmap.ArrayShapeError, ValueError),
    ("0-D ranges", POSE, np.array(1.0), B, covmap.ArrayShapeError, ValueError),
    ("string ranges", POSE, "1.0", B, covmap.ArrayDtypeError, TypeError),
    ("nested list ranges", POSE, [[1.0], [2.0], [0.5]], B, covmap.ArrayDtypeError, TypeError),
    ("pose of two", (1.0, 1.0), R, B, covmap.ArrayShapeError, ValueError),
    ("pose of four", np.array([1.0, 1.0, 0.0, 0.0]), R, B, covmap.ArrayShapeError, ValueError),
]


def ids() -> list[str]:
    return [c[0] for c in CASES]


def coverage_state(cmap: Any) -> list[Any]:
    return [cmap.histograms]


def occupancy_state(grid: Any) -> list[Any]:
    return [grid.log_odds(), grid.counts()]


# (map class, everything an integration may change)
MAPS = [(covmap.CoverageMap, coverage_state), (covmap.OccupancyGrid, occupancy_state)]


@pytest.mark.parametrize(("kind", "state"), MAPS, ids=["coverage", "occupancy"])
@pytest.mark.parametrize(("name", "pose", "ranges", "bearings", "cls", "builtin"), CASES, ids=ids())
def test_map_unchanged_after_error(
    scans: ScanSource,
    grid: covmap.Grid,
    model: Any,
    kind: Any,
    state: Any,
    name: str,
    pose: Any,
    ranges: Any,
    bearings: Any,
    cls: type[Exception],
    builtin: type[Exception],
) -> None:
    m = kind(grid)
    for scan in scans(grid, 5, seed=1):
        m.integrate(*scan, model)
    before = state(m)
    with pytest.raises(cls) as info:
        m.integrate(pose, ranges, bearings, model)
    assert type(info.value) is cls
    assert isinstance(info.value, builtin)
    assert isinstance(info.value, covmap.CovmapError)
    assert str(info.value), "the message says what was wrong"
    for after, was in zip(state(m), before, strict=True):
        np.testing.assert_array_equal(after, was)
    # Still usable afterwards.
    updates = m.integrate(POSE, R, B, model)
    assert updates is None or updates > 0  # CoverageMap counts its cell updates
    assert any(not np.array_equal(after, was) for after, was in zip(state(m), before, strict=True))


def test_error_messages_name_the_value(grid: covmap.Grid, model: Any) -> None:
    cmap = covmap.CoverageMap(grid)
    with pytest.raises(covmap.InvalidRangeError, match=r"index 2: -3"):
        cmap.integrate(POSE, np.array([1.0, 1.0, -3.0]), B, model)
    with pytest.raises(covmap.LengthMismatchError, match=r"3 vs 2"):
        cmap.integrate(POSE, R, B[:2], model)
    with pytest.raises(covmap.ArrayDtypeError, match=r"ranges must have dtype float64, got int64"):
        cmap.integrate(POSE, np.array([1, 2, 3]), B, model)
    with pytest.raises(covmap.ArrayShapeError, match=r"bearings must be a 1-D array"):
        cmap.integrate(POSE, R, np.zeros((3, 2)), model)


def test_wrong_argument_types_are_type_errors(grid: covmap.Grid, model: Any) -> None:
    cmap = covmap.CoverageMap(grid)
    before = cmap.histograms
    with pytest.raises(TypeError, match="SonarModel or a LaserModel"):
        cmap.integrate(POSE, R, B, "laser")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="pose"):
        cmap.integrate(("a", "b", "c"), R, B, model)  # type: ignore[arg-type]
    with pytest.raises(TypeError):
        covmap.CoverageMap("not a grid")  # type: ignore[arg-type]
    np.testing.assert_array_equal(cmap.histograms, before)


def test_every_error_class_derives_from_covmap_error() -> None:
    classes = [getattr(covmap, name) for name in covmap.__all__ if name.endswith("Error")]
    assert len(classes) == 18
    for cls in classes:
        assert issubclass(cls, covmap.CovmapError)
        assert cls is covmap.CovmapError or issubclass(cls, (ValueError, IndexError, TypeError, OSError))
    assert issubclass(covmap.CellOutOfBoundsError, IndexError)
    assert issubclass(covmap.ArrayDtypeError, TypeError)
    assert issubclass(covmap.FileIOError, OSError)
    for cls in (
        covmap.FileFormatError,
        covmap.InvalidPolygonError,
        covmap.InvalidValueError,
        covmap.UnknownWorldError,
    ):
        assert issubclass(cls, ValueError)
