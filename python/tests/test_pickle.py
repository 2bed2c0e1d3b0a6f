"""Every object that holds state pickles, and comes back equal to itself
in what it does."""

from __future__ import annotations

import copy
import pickle
from typing import Any

import numpy as np
import pytest

import covmap


def test_sensors_robot_and_planner_pickle_with_their_settings() -> None:
    ring = covmap.SonarRing(bearings_rad=np.radians([0.0, 45.0, 90.0]), noise_std_m=0.02, rays_per_cone=5)
    laser = covmap.Laser(bearings_rad=np.linspace(-1, 1, 11), max_range_m=12.0, noise_std_m=0.0)
    robot = covmap.Robot(radius_m=0.3)
    for thing in (ring, laser, robot):
        assert pickle.loads(pickle.dumps(thing)) == thing
        assert copy.deepcopy(thing) == thing
    planner = covmap.Planner(alpha=0.3, candidate_stride_m=0.7, range_step_m=0.2, stop_coverage="mean")
    back = pickle.loads(pickle.dumps(planner))
    assert repr(back) == repr(planner)
    world = covmap.World.builtin("office")
    poses = np.array([[2.0, 2.0, 0.0], [3.0, 2.5, 1.0]])
    np.testing.assert_array_equal(
        pickle.loads(pickle.dumps(ring)).simulate_path(world, poses, seed=4), ring.simulate_path(world, poses, seed=4)
    )


def test_worlds_pickle_with_their_polygons_and_materials() -> None:
    world = covmap.World.builtin("office")
    back = pickle.loads(pickle.dumps(world))
    assert len(back) == len(world) and back.materials == world.materials
    for a, b in zip(back.polygons, world.polygons):
        np.testing.assert_array_equal(a, b)
    grid = covmap.Grid.covering(world.bounds, resolution=0.25)
    np.testing.assert_array_equal(back.coverage(grid), world.coverage(grid))


def test_a_log_with_dropped_beams_pickles_and_copies() -> None:
    """A laser log's dropped beams (NaN ranges, as every REP 117 bag has)
    survive pickling and copying, still dropped."""
    log = covmap.Log.from_laser_scans(
        np.zeros((1, 3)),
        np.array([[np.nan, 1.0]]),
        angle_min=0.0,
        angle_increment=0.1,
        range_min=0.0,
        range_max=5.0,
    )
    for back in (pickle.loads(pickle.dumps(log)), copy.deepcopy(log)):
        ranges = back.ranges
        assert np.isnan(ranges[0, 0]) and ranges[0, 1] == 1.0


def _blank(cls: type) -> Any:
    return cls.__new__(cls)


class _Tampered:
    """Pickles as ``cls`` restored from ``state``, as a changed pickle would."""

    def __init__(self, cls: type, state: Any) -> None:
        self.cls, self.state = cls, state

    def __reduce__(self) -> tuple[Any, ...]:
        return (_blank, (self.cls,), self.state)


def _loaded(cls: type, state: Any) -> Any:
    return pickle.loads(pickle.dumps(_Tampered(cls, state)))


def test_a_tampered_exploration_result_is_refused_naming_the_field() -> None:
    result = covmap.explore(covmap.World.builtin("partial"), covmap.Strategy.frontier(), resolution=0.1, max_steps=2)
    state = dict(vars(result))
    back = _loaded(covmap.ExplorationResult, state)
    assert back.path_length_m == result.path_length_m and np.array_equal(back.truth, result.truth)
    other = covmap.CoverageMap(covmap.Grid(origin=(0.0, 0.0), resolution=0.1, shape=(2, 2)))
    for field, value in (
        ("truth", state["truth"] * 3.0),
        ("scanned", state["scanned"][:-1]),
        ("map", other),
        ("termination", "won"),
        ("seed", -1),
        ("steps", True),
        ("trace", {**state["trace"], "scans": np.arange(7)}),
        ("start", np.array([np.nan, 0.0, 0.0])),
        ("coverage_error", covmap.ExplorationErrors(2.0, 0.1)),
        ("strategy", "frontier"),
    ):
        with pytest.raises(covmap.InvalidValueError, match=f"not a saved ExplorationResult: {field}"):
            _loaded(covmap.ExplorationResult, {**state, field: value})
    with pytest.raises(covmap.InvalidValueError, match="expected the fields"):
        _loaded(covmap.ExplorationResult, {k: v for k, v in state.items() if k != "grid"})
    with pytest.raises(covmap.InvalidValueError, match="expected the fields"):
        _loaded(covmap.ExplorationResult, [1, 2])


def test_a_tampered_run_summary_is_refused_naming_the_field() -> None:
    summary = covmap.sweep([{"world": "partial", "strategy": "frontier", "resolution": 0.1, "max_steps": 2}], progress=False)[0]
    state = dict(vars(summary))
    assert _loaded(covmap.RunSummary, state) == summary
    for field, value in (
        ("index", -1),
        ("start", (1.0, 2.0)),
        ("options", {"not_a_keyword": 1}),
        ("high_entropy_fraction", 1.5),
        ("timing", "fast"),
        ("world", 3),
    ):
        with pytest.raises(covmap.InvalidValueError, match=f"not a saved RunSummary: {field}"):
            _loaded(covmap.RunSummary, {**state, field: value})
