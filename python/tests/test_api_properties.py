"""Property: every call of the Python API, with arguments of every kind,
either succeeds or raises a ``covmap.CovmapError`` (or, for an argument of
the wrong class, Python's ``TypeError`` naming it: ``wrong_type.py``), and
a map (or grid) a call raised on is exactly as it was."""

from __future__ import annotations

import math
from typing import Any, Callable

import numpy as np
import pytest

import covmap
from wrong_type import converted_argument

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

#: Examples per property: a few hundred calls each, a few seconds in all.
EXAMPLES = 150
SETTINGS = settings(
    max_examples=EXAMPLES,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)

GRID = covmap.Grid(origin=(0.0, 0.0), resolution=0.1, shape=(10, 12))
WORLD = covmap.World([[(0.2, 0.2), (0.6, 0.2), (0.6, 0.6)]])

#: Numbers of every kind: ordinary, zero, negative, huge, tiny, NaN and
#: infinite floats, integers beyond 64 bits, numpy scalars.
numbers = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.floats(min_value=-2.0, max_value=2.0),
    st.integers(min_value=-(2**70), max_value=2**70),
    st.sampled_from([0, -1, 1, 2**63, 2**64, -(2**63) - 1, 1e308, -1e308, 5e-324, math.nan, math.inf]),
    st.builds(np.float64, st.floats(allow_nan=True)),
    st.builds(np.float32, st.floats(width=32, allow_nan=True)),
)
#: Anything an argument could be given: numbers, strings, None, sequences
#: of numbers of any length, nested sequences, arrays of several dtypes
#: and shapes, other covmap objects.
values = st.recursive(
    st.one_of(
        numbers,
        st.text(max_size=5),
        st.binary(max_size=5),
        st.none(),
        st.booleans(),
        st.sampled_from([GRID, covmap.LaserModel(), covmap.SonarModel(), WORLD, object(), range(2**62)]),
        st.builds(
            lambda shape, dtype, fill: np.full(shape, fill).astype(dtype),
            st.lists(st.integers(0, 4), min_size=0, max_size=3).map(tuple),
            st.sampled_from([np.float64, np.float32, np.int64, np.float16, np.bool_]),
            st.floats(-3.0, 3.0),
        ),
    ),
    lambda inner: st.one_of(st.lists(inner, max_size=4), st.tuples(inner, inner), st.tuples(inner, inner, inner)),
    max_leaves=8,
)
#: Values near the valid ones: a pose, ranges and bearings of a few beams,
#: with any element replaced by any number.
poses = st.one_of(st.tuples(numbers, numbers, numbers), st.tuples(st.floats(0.0, 1.2), st.floats(0.0, 1.0), st.floats(-7.0, 7.0)), values)
readings = st.one_of(
    st.lists(numbers, max_size=6),
    st.lists(st.floats(0.0, 3.0), min_size=1, max_size=6).map(np.array),
    values,
)


def calls(drawn: st.DataObject, target: Any) -> list[Callable[[], Any]]:
    """The calls a property draws from: every method of a map, the grid,
    the world, the planner and the simulated sensors, with drawn arguments."""
    d = drawn.draw
    model = d(st.sampled_from([covmap.LaserModel(), covmap.SonarModel(), "laser", None]))
    return [
        lambda: target.integrate(d(poses), d(readings), d(readings), model),
        lambda: target.integrate(d(poses), d(readings), d(readings), d(values)),
        lambda: target.observed(),
        lambda: target.grid.cell_center(d(values), d(values)),
        lambda: target.grid.contains(d(values), d(values)),
        lambda: target.grid.world_to_cell(d(numbers), d(numbers)),
    ]


def coverage_map_calls(drawn: st.DataObject, m: covmap.CoverageMap) -> list[Callable[[], Any]]:
    d = drawn.draw
    return [
        lambda: m.histogram(d(values), d(values)),
        lambda: m.track_history(d(values)),
        lambda: m.ros_occupancy(source=d(values), unknown_within_nats=d(numbers)),
        lambda: covmap.expected_information_gain(m, d(values), d(readings), covmap.LaserModel(), d(st.sampled_from(["fast", "exact", "x"]))),
        lambda: covmap.Planner(alpha=d(numbers)).status(m, d(poses)),
        lambda: covmap.Planner(robot_radius_m=d(st.one_of(numbers, st.none()))).path_costs(m, d(poses)),
        lambda: covmap.CoverageMap.from_histograms(GRID, d(values)),
        lambda: covmap.CoverageMap(d(values), d(values)),
    ]


def state(target: Any) -> tuple[bytes, ...]:
    """A map's whole observable state."""
    if isinstance(target, covmap.CoverageMap):
        return (target.histograms.tobytes(), target.measurements().tobytes(), bytes([target.tracks_history]))
    return (target.log_odds().tobytes(), target.counts().tobytes())


def check(call: Callable[[], Any], target: Any) -> None:
    """The call succeeds, or raises a CovmapError (or the TypeError of an
    argument of the wrong class) and leaves ``target`` as it was."""
    before = state(target)
    try:
        call()
    except covmap.CovmapError:
        assert state(target) == before, "a call that raised changed the map"
    except TypeError as e:
        if converted_argument(e) is None:
            raise
        assert state(target) == before, "a call that raised changed the map"


@SETTINGS
@given(st.data())
def test_every_coverage_map_call_succeeds_or_raises_a_covmap_error(data: st.DataObject) -> None:
    m = covmap.CoverageMap(GRID)
    m.track_history(True)
    m.integrate((0.5, 0.5, 0.0), [0.4, 0.8], [0.0, 1.0], covmap.LaserModel())
    for _ in range(3):
        every = calls(data, m) + coverage_map_calls(data, m)
        check(data.draw(st.sampled_from(every)), m)


@SETTINGS
@given(st.data())
def test_every_occupancy_grid_call_succeeds_or_raises_a_covmap_error(data: st.DataObject) -> None:
    o = covmap.OccupancyGrid(GRID)
    for _ in range(3):
        check(data.draw(st.sampled_from(calls(data, o))), o)


@SETTINGS
@given(st.data())
def test_every_constructor_and_simulation_succeeds_or_raises_a_covmap_error(data: st.DataObject) -> None:
    d = data.draw
    every: list[Callable[[], Any]] = [
        lambda: covmap.Grid(origin=d(values), resolution=d(values), shape=d(values)),
        lambda: covmap.Grid.covering(d(values), resolution=d(numbers)),
        lambda: covmap.LaserModel(max_range_m=d(st.one_of(numbers, st.none())), band_m=d(st.one_of(numbers, st.none()))),
        lambda: covmap.SonarModel(opening_angle_rad=d(st.one_of(numbers, st.none())), xi_min=d(st.one_of(numbers, st.none()))),
        lambda: covmap.LaserModel().kernel(d(values), d(numbers), resolution=d(numbers), bins=d(values)),
        lambda: covmap.Laser(d(values), d(values)),
        lambda: covmap.Laser(bearings_rad=d(readings)).simulate(WORLD, d(poses), seed=d(values)),
        lambda: covmap.SonarRing(bearings_rad=d(readings), rays_per_cone=d(st.one_of(st.none(), numbers))).simulate_path(WORLD, d(values)),
        lambda: covmap.SonarRing.ring(d(values)),
        lambda: covmap.World(d(values), d(values)),
        lambda: WORLD.cast(d(values), d(readings), d(numbers)),
        lambda: WORLD.coverage(covmap.Grid(origin=(0.0, 0.0), resolution=d(st.floats(0.01, 10.0)), shape=(d(st.integers(1, 50)), d(st.integers(1, 50))))),
        lambda: WORLD.distance_to_obstacle(d(values), d(values)),
        lambda: covmap.Robot(radius_m=d(numbers)).clearance(WORLD, d(values)),
        lambda: covmap.Robot().free_travel(WORLD, d(values), d(values)),
        lambda: covmap.Log(d(values), d(values), d(readings), max_range_m=d(numbers)),
        lambda: covmap.Log.from_laser_scans(d(values), d(values), angle_min=d(numbers), angle_increment=d(numbers), range_min=d(numbers), range_max=d(numbers)),
        lambda: covmap.Strategy.counting(d(values), d(values)),
        lambda: covmap.Strategy.coverage(d(values)),
    ]
    for _ in range(3):
        try:
            d(st.sampled_from(every))()
        except covmap.CovmapError:
            pass
