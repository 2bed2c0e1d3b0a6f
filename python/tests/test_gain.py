"""The expected information gain of viewpoints (paper eq. 11-13)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
import pytest

import covmap

if TYPE_CHECKING:
    from conftest import ScanSource

RING = np.linspace(0.0, 2 * math.pi, 24, endpoint=False)


def small_grid() -> covmap.Grid:
    """2 m x 1.5 m at 5 cm."""
    return covmap.Grid(origin=(0.0, 0.0), resolution=0.05, shape=(30, 40))


def candidate_poses(grid: covmap.Grid, count: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    x0, y0, x1, y1 = grid.bounds
    return np.column_stack(
        [rng.uniform(x0, x1 - 1e-9, count), rng.uniform(y0, y1 - 1e-9, count), rng.uniform(-3, 3, count)]
    )


@pytest.mark.parametrize("stop_coverage", ["ml", "mean"])
def test_fast_equals_exact(scans: ScanSource, model: Any, stop_coverage: Literal["ml", "mean"]) -> None:
    grid = small_grid()
    cmap = covmap.CoverageMap(grid)
    for scan in scans(grid, 12, seed=3, beams=12):
        cmap.integrate(*scan, model)
    poses = candidate_poses(grid, 10, seed=4)
    bearings = RING[::3]
    fast = covmap.expected_information_gain(cmap, poses, bearings, model, stop_coverage=stop_coverage)
    exact = covmap.expected_information_gain(
        cmap, poses, bearings, model, method="exact", stop_coverage=stop_coverage
    )
    # `method` may also be given by position, as the fifth argument.
    positional = covmap.expected_information_gain(cmap, poses, bearings, model, "exact", stop_coverage=stop_coverage)
    np.testing.assert_array_equal(positional, exact)
    assert fast.shape == (10,) and fast.dtype == np.float64
    assert np.all(exact > 0.0)
    np.testing.assert_allclose(fast, exact, rtol=1e-6)


def test_prior_map_gains_everywhere(model: Any) -> None:
    cmap = covmap.CoverageMap(small_grid())
    poses = candidate_poses(cmap.grid, 20, seed=1)
    gains = covmap.expected_information_gain(cmap, poses, RING, model)
    assert np.all(gains > 0.0)
    # Unknown space predicted transparent (ML) is worth more than opaque (mean).
    mean = covmap.expected_information_gain(cmap, poses, RING, model, stop_coverage="mean")
    assert np.all(mean < gains)


def test_certain_map_gains_nothing(model: Any) -> None:
    grid = small_grid()
    one_hot = np.zeros((*grid.shape, 16), dtype=np.float32)
    one_hot[..., 0] = 1.0  # every cell certainly empty
    cmap = covmap.CoverageMap.from_histograms(grid, one_hot)
    gains = covmap.expected_information_gain(cmap, candidate_poses(grid, 5, seed=2), RING, model)
    np.testing.assert_allclose(gains, 0.0, atol=1e-9)


def test_sequences_and_empty_inputs(model: Any) -> None:
    cmap = covmap.CoverageMap(small_grid())
    as_array = covmap.expected_information_gain(cmap, np.array([[1.0, 0.7, 0.0]]), np.array([0.0, 1.0]), model)
    as_lists = covmap.expected_information_gain(cmap, [(1.0, 0.7, 0.0)], [0.0, 1.0], model)
    np.testing.assert_array_equal(as_array, as_lists)
    empty = covmap.expected_information_gain(cmap, np.zeros((0, 3)), RING, model)
    assert empty.shape == (0,)
    finer = covmap.expected_information_gain(cmap, [(1.0, 0.7, 0.0)], [0.0], model, range_step_m=0.01)
    assert finer[0] > 0.0


@pytest.mark.parametrize(
    ("poses", "kwargs", "cls"),
    [
        ([(1.0, 0.7, 0.0)], {"method": "slow"}, covmap.InvalidParameterError),
        ([(1.0, 0.7, 0.0)], {"stop_coverage": "median"}, covmap.InvalidParameterError),
        ([(1.0, 0.7, 0.0)], {"range_step_m": 0.1}, covmap.InvalidParameterError),
        ([(1.0, 0.7, 0.0)], {"range_step_m": -0.01}, covmap.InvalidParameterError),
        ([(math.nan, 0.7, 0.0)], {}, covmap.InvalidPoseError),
        ([(1.0, 0.7, math.inf)], {}, covmap.InvalidPoseError),
        ([(5.0, 0.7, 0.0)], {}, covmap.PoseOutsideMapError),
        (np.zeros((2, 2)), {}, covmap.ArrayShapeError),
        (np.zeros(3), {}, covmap.ArrayShapeError),
        (np.full((2, 3), 0.5, dtype=np.float16), {}, covmap.ArrayDtypeError),
        ([(1.0, 0.7)], {}, covmap.ArrayShapeError),
    ],
    ids=["method", "stop", "coarse step", "negative step", "nan pose", "inf heading", "outside", "2 columns",
         "1-D", "float16", "pair"],
)
def test_bad_input_raises_and_leaves_the_map(
    scans: ScanSource, model: Any, poses: Any, kwargs: dict[str, Any], cls: type[Exception]
) -> None:
    grid = small_grid()
    cmap = covmap.CoverageMap(grid)
    for scan in scans(grid, 3, seed=5):
        cmap.integrate(*scan, model)
    before = cmap.histograms
    with pytest.raises(cls) as info:
        covmap.expected_information_gain(cmap, poses, RING, model, **kwargs)
    assert isinstance(info.value, covmap.CovmapError)
    assert isinstance(info.value, TypeError if cls is covmap.ArrayDtypeError else ValueError)
    np.testing.assert_array_equal(cmap.histograms, before)


def test_bad_bearings_and_models(model: Any) -> None:
    cmap = covmap.CoverageMap(small_grid())
    with pytest.raises(covmap.InvalidBearingError):
        covmap.expected_information_gain(cmap, [(1.0, 0.7, 0.0)], [0.0, math.nan], model)
    with pytest.raises(TypeError, match="SonarModel or a LaserModel"):
        covmap.expected_information_gain(cmap, [(1.0, 0.7, 0.0)], [0.0], "sonar")  # type: ignore[arg-type]
