"""Bad input raises a specific error and leaves the map exactly as it was."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np
import pytest

import covmap
from wrong_type import converted_argument

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
    ("float16 bearings", POSE, R, B.astype(np.float16), covmap.ArrayDtypeError, TypeError),
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
    with pytest.raises(covmap.InvalidTypeError, match="SonarModel or a LaserModel"):
        cmap.integrate(POSE, R, B, "laser")  # type: ignore[arg-type]
    with pytest.raises(covmap.InvalidTypeError, match="SonarModel or a LaserModel"):
        cmap.integrate(POSE, R, B, None)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="pose"):
        cmap.integrate(("a", "b", "c"), R, B, model)  # type: ignore[arg-type]
    with pytest.raises(TypeError):
        covmap.CoverageMap("not a grid")  # type: ignore[arg-type]
    np.testing.assert_array_equal(cmap.histograms, before)


def test_every_error_class_derives_from_covmap_error() -> None:
    classes = [getattr(covmap, name) for name in covmap.__all__ if name.endswith("Error")]
    assert len(classes) == 32
    for cls in classes:
        assert issubclass(cls, covmap.CovmapError)
        # RobotError is no bad input: a robot's sensor or drive failed during a
        # run; SweepError, that some runs of a sweep raised; MainGuardError,
        # that a script runs a sweep where its workers would run it again;
        # MapBusyError, that a map was used inside its own integrate_log.
        no_bad_input = (covmap.CovmapError, covmap.RobotError, covmap.SweepError, covmap.MainGuardError, covmap.MapBusyError)
        assert cls in no_bad_input or issubclass(
            cls, (ValueError, IndexError, TypeError, OSError, ImportError, MemoryError)
        )
    assert issubclass(covmap.SweepError, RuntimeError) and not issubclass(covmap.SweepError, ValueError)
    assert issubclass(covmap.InvalidSpecError, ValueError) and issubclass(covmap.InvalidExecutorError, ValueError)
    assert issubclass(covmap.SchedulerError, OSError) and issubclass(covmap.MissingDependencyError, ImportError)
    assert issubclass(covmap.RobotError, RuntimeError) and not issubclass(covmap.RobotError, ValueError)
    assert issubclass(covmap.MainGuardError, RuntimeError) and issubclass(covmap.MapBusyError, RuntimeError)
    assert issubclass(covmap.InvalidStartError, ValueError) and issubclass(covmap.InvalidGoalError, ValueError)
    assert issubclass(covmap.InvalidActionError, ValueError)
    assert issubclass(covmap.IntegerOverflowError, OverflowError) and issubclass(covmap.IntegerOverflowError, ValueError)
    assert issubclass(covmap.OutOfMemoryError, MemoryError)
    assert issubclass(covmap.CellOutOfBoundsError, IndexError)
    assert issubclass(covmap.ArrayDtypeError, TypeError)
    assert issubclass(covmap.InvalidTypeError, TypeError)
    assert issubclass(covmap.FileIOError, OSError)
    for cls in (
        covmap.FileFormatError,
        covmap.InvalidPolygonError,
        covmap.InvalidValueError,
        covmap.UnknownWorldError,
    ):
        assert issubclass(cls, ValueError)


def test_a_huge_heading_or_bearing_is_the_direction_it_names(grid: covmap.Grid) -> None:
    """A finite but huge heading plus bearing updates the cells of the
    direction its sine and cosine give, as the same direction written small
    does; one that overflows is an InvalidBearingError."""
    sonar = covmap.SonarModel()
    small = math.atan2(math.sin(1e16), math.cos(1e16))
    maps = []
    for pose, bearing in (((1.5, 1.0, 0.0), 1e16), ((1.5, 1.0, 1e16), 0.0), ((1.5, 1.0, 0.0), small)):
        cmap = covmap.CoverageMap(grid)
        assert cmap.integrate(pose, np.array([0.8]), np.array([bearing]), sonar) > 50
        maps.append(cmap.histograms)
    np.testing.assert_array_equal(maps[0], maps[2])
    np.testing.assert_array_equal(maps[1], maps[2])
    cmap = covmap.CoverageMap(grid)
    before = cmap.histograms
    with pytest.raises(covmap.InvalidBearingError):
        cmap.integrate((1.5, 1.0, 1e308), np.array([0.8]), np.array([1e308]), sonar)
    np.testing.assert_array_equal(cmap.histograms, before)


def test_seeds_are_integers_from_0_to_2_to_the_64(grid: covmap.Grid) -> None:
    world = covmap.World.builtin("corridor")
    ring = covmap.SonarRing()
    for bad in (-1, 2**64):
        with pytest.raises(covmap.InvalidParameterError, match="seed"):
            ring.simulate(world, (2.0, 1.3, 0.0), seed=bad)
        with pytest.raises(covmap.InvalidParameterError, match="seed"):
            covmap.Laser().simulate_path(world, np.array([[2.0, 1.3, 0.0]]), seed=bad)
    for wrong in ("1", 1.5, None):
        with pytest.raises(covmap.InvalidTypeError, match="seed"):
            ring.simulate(world, (2.0, 1.3, 0.0), seed=wrong)  # type: ignore[arg-type]
    a = ring.simulate(world, (2.0, 1.3, 0.0), seed=np.uint64(2**64 - 1))
    b = ring.simulate(world, (2.0, 1.3, 0.0), seed=2**64 - 1)
    np.testing.assert_array_equal(a[0], b[0])


def test_sensor_counts_are_bounded_before_anything_is_allocated() -> None:
    with pytest.raises(covmap.InvalidParameterError):
        covmap.SonarRing.ring(2**40)
    with pytest.raises(covmap.InvalidParameterError):
        covmap.Laser(2**40)
    assert len(covmap.SonarRing.ring(65536).bearings_rad) == 65536


def test_values_of_the_wrong_type_are_covmap_errors(grid: covmap.Grid) -> None:
    square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
    with pytest.raises(covmap.InvalidTypeError, match="materials"):
        covmap.World([square], "wall")  # type: ignore[arg-type]
    with pytest.raises(covmap.InvalidTypeError, match="polygons"):
        covmap.World(5)  # type: ignore[arg-type]
    with pytest.raises(covmap.InvalidTypeError):
        covmap.Laser(5, bearings_rad=[0.0])
    cmap = covmap.CoverageMap(grid)
    with pytest.raises(covmap.InvalidTypeError, match="state"):
        cmap.__setstate__((1,))
    with pytest.raises(covmap.ArrayShapeError, match="origin"):
        covmap.Grid(origin=(0.0, 0.0, 0.0), resolution=1.0, shape=(2, 2))  # type: ignore[arg-type]
    # Any cell has a centre, on the grid or not.
    assert grid.cell_center(-1, 0) == pytest.approx((grid.origin[0] + 0.5 * grid.resolution, grid.origin[1] - 0.5 * grid.resolution))


def test_an_impossible_entropy_history_is_refused(grid: covmap.Grid) -> None:
    cmap = covmap.CoverageMap(grid)
    cmap.track_history(True)
    cmap.integrate(POSE, R, B, covmap.SonarModel())
    rebuild, args, (history, evidence) = cmap.__reduce__()
    entropies, counts = history
    entropies = entropies.copy()
    entropies.flat[0] = 100.0  # more than ln(16) nats
    fresh = rebuild(*args)  # the map's histograms, without its history
    with pytest.raises(covmap.InvalidHistoryError):
        fresh.__setstate__(((entropies, counts), evidence))
    with pytest.raises(covmap.InvalidHistoryError):
        fresh.__setstate__((entropies, counts))  # the state saved before the evidence was kept


def test_points_that_are_not_finite_are_invalid_values() -> None:
    robot, world = covmap.Robot(), covmap.World.builtin("corridor")
    with pytest.raises(covmap.InvalidValueError):
        robot.clearance(world, np.array([[math.nan, 0.0]]))
    for x, y in ((math.nan, 0.0), (math.inf, 0.0)):
        with pytest.raises(covmap.InvalidValueError):
            world.distance_to_obstacle(x, y)
    with pytest.raises(covmap.InvalidValueError):
        robot.free_travel(world, (1.0, 1.3), (math.nan, 1.3))
    # A goal far beyond the world is as free as the wall in between allows.
    near, far = robot.free_travel(world, (2.0, 1.3), (1e3, 1.3)), robot.free_travel(world, (2.0, 1.3), (1e155, 1.3))
    assert 0.0 < near < 100.0
    assert far == pytest.approx(near)


def test_degenerate_grids_are_refused() -> None:
    for origin, resolution in (((0.0, 0.0), 1e-310), ((0.0, 0.0), 1e-7), ((1e17, 0.0), 0.05)):
        with pytest.raises(covmap.InvalidGridError):
            covmap.Grid(origin=origin, resolution=resolution, shape=(4, 4))
    with pytest.raises(covmap.InvalidParameterError):
        covmap.LaserModel().kernel(0.5, 1.0, resolution=5e-324)


def test_masked_arrays_are_refused(grid: covmap.Grid) -> None:
    cmap = covmap.CoverageMap(grid)
    before = cmap.histograms
    masked = np.ma.masked_array(R, mask=[False, True, False])
    with pytest.raises(covmap.ArrayDtypeError, match="masked"):
        cmap.integrate(POSE, masked, B, covmap.SonarModel())
    np.testing.assert_array_equal(cmap.histograms, before)
    # Nothing masked: the data, as a plain array gives it.
    plain = covmap.CoverageMap(grid)
    plain.integrate(POSE, R, B, covmap.SonarModel())
    cmap.integrate(POSE, np.ma.masked_array(R), B, covmap.SonarModel())
    np.testing.assert_array_equal(cmap.histograms, plain.histograms)


@pytest.mark.parametrize(
    ("call", "cls", "builtin", "argument"),
    [
        (lambda g: covmap.CoverageMap(g, 2**63), covmap.IntegerOverflowError, OverflowError, "bins"),
        (lambda g: covmap.CoverageMap(g, "16"), covmap.InvalidTypeError, TypeError, "bins"),
        (lambda g: g.cell_center(0, 2**64), covmap.IntegerOverflowError, OverflowError, "col"),
        (lambda g: covmap.Grid(origin=(0.0, 0.0), resolution=0.1, shape=(1, 2, 3)), covmap.ArrayShapeError, ValueError, "shape"),
        (lambda g: covmap.Planner(alpha="half"), covmap.InvalidTypeError, TypeError, "alpha"),
        (lambda g: covmap.Strategy.counting(True), covmap.InvalidTypeError, TypeError, "n"),
        (lambda g: covmap.Planner(alpha=10**400), covmap.IntegerOverflowError, OverflowError, "alpha"),
    ],
    ids=["int 2**63", "str for int", "int 2**64", "tuple of three", "str for float", "bool for int", "int for float"],
)
def test_numbers_python_cannot_convert_raise_covmap_errors_naming_them(
    grid: covmap.Grid, call: Any, cls: type[Exception], builtin: type[Exception], argument: str
) -> None:
    with pytest.raises(cls, match=f"argument '{argument}'") as raised:
        call(grid)
    assert isinstance(raised.value, builtin)


def test_an_object_of_the_wrong_class_raises_pythons_type_error_naming_the_argument() -> None:
    with pytest.raises(TypeError, match="not an instance of 'Grid'") as raised:
        covmap.OccupancyGrid("grid")  # type: ignore[arg-type]
    assert converted_argument(raised.value) == "grid"


def test_a_huge_value_is_quoted_in_part() -> None:
    with pytest.raises(covmap.IntegerOverflowError) as raised:
        covmap.Strategy.counting(10**5000)  # more digits than Python prints
    assert "an integer of 16610 bits" in str(raised.value) and len(str(raised.value)) < 200
    with pytest.raises(covmap.IntegerOverflowError) as raised:
        covmap.Strategy.counting(10**1000)
    assert "(1001 characters)" in str(raised.value) and len(str(raised.value)) < 200


def test_a_sequence_is_never_reserved_by_its_claimed_length(grid: covmap.Grid) -> None:
    cmap = covmap.CoverageMap(grid)
    with pytest.raises(covmap.ArrayShapeError, match="65536"):
        cmap.integrate((1.0, 1.0, 0.0), range(2**62), np.zeros(3), covmap.LaserModel())
    with pytest.raises(covmap.ArrayShapeError, match="ranges"):
        cmap.integrate((1.0, 1.0, 0.0), np.broadcast_to(1.0, (2**40,)), np.zeros(3), covmap.LaserModel())
