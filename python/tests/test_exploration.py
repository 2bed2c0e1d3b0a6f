"""covmap.explore, covmap.Exploration and covmap.Strategy as a user calls
them: sane and consistent figures, determinism, pickling, stepping, and bad
input refused before anything runs."""

from __future__ import annotations

import copy
import inspect
import math
import pickle
import re
from typing import Any

import numpy as np
import pytest

import covmap

BY_RULE = {"certain", "stagnated", "no_goal"}
STEPS = 8
"""Steps of the short corridor runs: enough to drive, scan and contact."""


def room(width: float = 4.0, height: float = 3.0, wall: float = 0.1) -> covmap.World:
    """A closed room with a half-height wall in its middle: small enough to
    explore to the end in a fraction of a second at 10 cm cells."""
    w, h, t = width, height, wall
    return covmap.World(
        [
            [(0, 0), (w, 0), (w, t), (0, t)],
            [(0, h - t), (w, h - t), (w, h), (0, h)],
            [(0, 0), (t, 0), (t, h), (0, h)],
            [(w - t, 0), (w, 0), (w, h), (w - t, h)],
            [(1.8, 0), (2.0, 0), (2.0, 1.8), (1.8, 1.8)],
        ]
    )


@pytest.fixture(scope="module")
def corridor() -> covmap.World:
    return covmap.World.builtin("corridor")


@pytest.fixture(scope="module")
def short_run(corridor: covmap.World) -> covmap.ExplorationResult:
    """Eight steps of the paper's strategy through the corridor."""
    return covmap.explore(corridor, covmap.Strategy.coverage(0.5), seed=3, max_steps=STEPS)


def travelled(trajectory: np.ndarray) -> float:
    return float(np.hypot(*np.diff(trajectory[:, :2], axis=0).T).sum())


def assert_same_run(a: covmap.ExplorationResult, b: covmap.ExplorationResult) -> None:
    """Two results of the same run: every outcome equal (wall times aside)."""
    assert a.strategy == b.strategy and a.seed == b.seed and a.grid == b.grid
    assert (a.termination, a.path_length_m, a.scans, a.steps, a.contacts) == (
        b.termination,
        b.path_length_m,
        b.scans,
        b.steps,
        b.contacts,
    )
    np.testing.assert_array_equal(a.start, b.start)
    np.testing.assert_array_equal(a.trajectory, b.trajectory)
    np.testing.assert_array_equal(a.scanned, b.scanned)
    np.testing.assert_array_equal(a.map.histograms, b.map.histograms)
    np.testing.assert_array_equal(a.map.measurements(), b.map.measurements())
    np.testing.assert_array_equal(a.occupancy.log_odds(), b.occupancy.log_odds())
    np.testing.assert_array_equal(a.counts, b.counts)
    np.testing.assert_array_equal(a.truth, b.truth)
    np.testing.assert_array_equal(a.evaluation_cells, b.evaluation_cells)
    assert a.high_entropy_fraction == b.high_entropy_fraction
    assert a.coverage_error == b.coverage_error
    assert a.trace.keys() == b.trace.keys()
    for key in a.trace.keys() - {"planning_s"}:
        np.testing.assert_array_equal(a.trace[key], b.trace[key], err_msg=key)


# -- Strategy ---------------------------------------------------------------


def test_strategies_show_compare_hash_and_pickle() -> None:
    strategies = [
        covmap.Strategy.coverage(),
        covmap.Strategy.coverage(alpha=0.25),
        covmap.Strategy.counting(),
        covmap.Strategy.counting(1),
        covmap.Strategy.counting(n=50, discount_beyond_m=covmap.DEFAULT_DISCOUNT_BEYOND_M),
        covmap.Strategy.frontier(),
    ]
    assert [repr(s) for s in strategies] == [
        "Strategy.coverage(alpha=0.5)",
        "Strategy.coverage(alpha=0.25)",
        "Strategy.counting(n=50, discount_beyond_m=None)",
        "Strategy.counting(n=1, discount_beyond_m=None)",
        "Strategy.counting(n=50, discount_beyond_m=2.0)",
        "Strategy.frontier()",
    ]
    assert len(set(strategies)) == len(strategies)
    for s in strategies:
        for back in (pickle.loads(pickle.dumps(s)), copy.deepcopy(s), eval(repr(s), {"Strategy": covmap.Strategy})):
            assert back == s and hash(back) == hash(s) and repr(back) == repr(s)
    coverage, _, counting, _, discounted, frontier = strategies
    assert (coverage.name, coverage.alpha, coverage.n, coverage.discount_beyond_m) == ("coverage", 0.5, None, None)
    assert (counting.name, counting.alpha, counting.n) == ("counting", None, 50)
    assert discounted.discount_beyond_m == covmap.DEFAULT_DISCOUNT_BEYOND_M == 2.0
    assert (frontier.name, frontier.alpha, frontier.n) == ("frontier", None, None)
    assert covmap.Strategy.coverage(0.5) != covmap.Strategy.counting(1)


@pytest.mark.parametrize(
    ("build", "name", "value"),
    [
        (lambda: covmap.Strategy.coverage(1.5), "alpha", "1.5"),
        (lambda: covmap.Strategy.coverage(-0.1), "alpha", "-0.1"),
        (lambda: covmap.Strategy.coverage(math.nan), "alpha", "NaN"),
        (lambda: covmap.Strategy.counting(0), "n", "0"),
        (lambda: covmap.Strategy.counting(-3), "n", "-3"),
        (lambda: covmap.Strategy.counting(2**64), "n", "18446744073709551616"),
        (lambda: covmap.Strategy.counting(50, -1.0), "discount_beyond_m", "-1"),
        (lambda: covmap.Strategy.counting(50, 0.0), "discount_beyond_m", "0"),
        (lambda: covmap.Strategy.counting(50, math.inf), "discount_beyond_m", "inf"),
    ],
)
def test_a_bad_strategy_setting_is_named(build: Any, name: str, value: str) -> None:
    # The core names a value it refuses, the binding an integer no count takes.
    said = f"argument '{name}': {value} is out of range" if name == "n" else f"`{name}` = {value}"
    with pytest.raises(covmap.InvalidParameterError, match=re.escape(said)) as raised:
        build()
    assert isinstance(raised.value, ValueError)
    if name == "n":  # the range n really takes, not a Rust integer's
        assert "expected an integer from 1 to 2**32 - 1" in str(raised.value)


# -- explore ----------------------------------------------------------------


def test_a_short_run_reports_consistent_figures(short_run: covmap.ExplorationResult) -> None:
    r = short_run
    rows_cols = r.grid.shape
    assert r.termination == "limit" and r.steps == STEPS
    assert r.strategy == covmap.Strategy.coverage(0.5) and r.seed == 3
    # Path length is the trajectory's length; every scan is marked on it.
    assert r.path_length_m > 1.0
    assert r.path_length_m == pytest.approx(travelled(r.trajectory), rel=1e-12, abs=1e-9)
    assert r.trajectory.shape == (len(r.scanned), 3) and r.scanned.dtype == np.bool_
    assert r.scans == int(r.scanned.sum()) >= STEPS
    np.testing.assert_array_equal(r.trajectory[0], r.start)
    np.testing.assert_array_equal(r.scan_poses, r.trajectory[r.scanned])
    # The per-step trace ends where the run does.
    assert set(r.trace) == {"path_length_m", "scans", "uncertain_fraction", "contact", "planning_s"}
    assert all(len(v) == r.steps for v in r.trace.values())
    assert r.trace["path_length_m"][-1] == r.path_length_m and r.trace["scans"][-1] == r.scans
    assert np.all(np.diff(r.trace["path_length_m"]) >= 0) and np.all(np.diff(r.trace["scans"]) >= 0)
    assert int(r.trace["contact"].sum()) == r.contacts
    # Table I's measure is the uncertain share of the evaluation cells.
    for a in (r.truth, r.evaluation_cells, r.counts, r.uncertain_cells):
        assert a.shape == rows_cols
    assert r.evaluation_cells.dtype == np.bool_ and r.evaluation_cells.any()
    assert r.high_entropy_fraction == r.uncertain_cells.sum() / r.evaluation_cells.sum()
    assert r.trace["uncertain_fraction"][-1] == pytest.approx(r.high_entropy_fraction)
    assert 0.0 < r.high_entropy_fraction < 1.0 and r.epsilon == 0.65
    assert 0.0 < r.coverage_error.coverage_map < 0.5 and 0.0 < r.coverage_error.occupancy < 0.5
    # The maps are the run's, on its grid, fed the same beams.
    assert r.map.grid == r.occupancy.grid == r.grid and r.map.tracks_history
    assert r.counts.sum() > 0 and np.array_equal(r.counts, r.occupancy.counts())
    assert r.timing.total_s > 0 and r.seconds >= r.timing.total_s
    assert r.real_time_factor() == pytest.approx(r.path_length_m / 0.5 / r.seconds)
    assert "limit" in repr(r)


def test_the_same_seed_gives_the_same_run(corridor: covmap.World, short_run: covmap.ExplorationResult) -> None:
    again = covmap.explore(corridor, covmap.Strategy.coverage(0.5), seed=3, max_steps=STEPS)
    assert_same_run(short_run, again)
    other = covmap.explore(corridor, covmap.Strategy.coverage(0.5), seed=4, max_steps=STEPS)
    assert not np.array_equal(other.start, short_run.start)


def test_a_result_pickles_whole(short_run: covmap.ExplorationResult) -> None:
    back = pickle.loads(pickle.dumps(short_run))
    assert_same_run(short_run, back)
    assert back.timing == short_run.timing and back.seconds == short_run.seconds
    assert back.map.tracks_history
    np.testing.assert_array_equal(back.map.stagnated(), short_run.map.stagnated())


def test_observed_cells_are_where_the_scans_went(grid: covmap.Grid, short_run: covmap.ExplorationResult) -> None:
    fresh = covmap.CoverageMap(grid)
    occupancy = covmap.OccupancyGrid(grid)
    assert not fresh.observed().any() and not occupancy.observed().any()
    assert fresh.observed().shape == grid.shape and fresh.observed().dtype == np.bool_
    pose, ranges, bearings = (1.0, 1.0, 0.0), np.array([1.0]), np.array([0.0])
    fresh.integrate(pose, ranges, bearings, covmap.LaserModel())
    occupancy.integrate(pose, ranges, bearings, covmap.LaserModel())
    for observed in (fresh.observed(), occupancy.observed()):
        assert observed[20, 30] and observed[20, 39]  # along the beam, its end
        assert not observed[5, 5] and not observed[20, 10]  # beside, behind the sensor
    # Where the robot scanned, its maps have seen; unobserved ML reads 0, as free does.
    r = short_run
    observed = r.map.observed()
    for x, y, _ in r.scan_poses:
        cell = r.grid.world_to_cell(x, y)
        assert cell is not None and observed[cell] and r.occupancy.observed()[cell]
    assert (~observed).any() and np.all(r.map.ml()[~observed] == 0.0)


def test_the_signature_shows_the_simulators_defaults() -> None:
    defaults = covmap._native._EXPLORE_DEFAULTS
    for function in (covmap.explore, covmap.Exploration):
        parameters = inspect.signature(function).parameters
        assert list(parameters)[:2] == ["world", "strategy"]
        shown = {name: p.default for name, p in parameters.items() if p.kind is inspect.Parameter.KEYWORD_ONLY}
        assert shown == defaults


@pytest.mark.parametrize(
    "strategy",
    [
        covmap.Strategy.coverage(0.5),
        covmap.Strategy.counting(1),
        covmap.Strategy.counting(50, covmap.DEFAULT_DISCOUNT_BEYOND_M),
        covmap.Strategy.frontier(),
    ],
    ids=repr,
)
def test_every_strategy_explores_a_room_to_its_end_by_rule(strategy: covmap.Strategy) -> None:
    r = covmap.explore(room(), strategy, seed=1, resolution=0.1)
    assert r.termination in BY_RULE, r
    assert r.path_length_m == pytest.approx(travelled(r.trajectory), abs=1e-9)
    assert r.high_entropy_fraction < 0.6


def test_a_laser_with_its_model_explores_too() -> None:
    r = covmap.explore(room(), covmap.Strategy.coverage(), sensor=covmap.Laser.sick_361(), resolution=0.1, max_steps=3)
    sonar = covmap.explore(room(), covmap.Strategy.coverage(), resolution=0.1, max_steps=3)
    assert 1 <= r.steps <= 3 and r.scans >= r.steps
    assert not np.array_equal(r.map.histograms, sonar.map.histograms)
    # The laser's model by default; the same with it given.
    given = covmap.explore(
        room(),
        covmap.Strategy.coverage(),
        sensor=covmap.Laser.sick_361(),
        model=covmap.LaserModel(),
        resolution=0.1,
        max_steps=3,
    )
    np.testing.assert_array_equal(given.map.histograms, r.map.histograms)


def test_a_given_start_is_where_the_robot_starts() -> None:
    r = covmap.explore(room(), covmap.Strategy.frontier(), start=(1.0, 1.5, 0.5), resolution=0.1, max_steps=2)
    np.testing.assert_array_equal(r.start, [1.0, 1.5, 0.5])
    np.testing.assert_array_equal(r.trajectory[0], [1.0, 1.5, 0.5])


# -- Exploration ------------------------------------------------------------


def test_stepping_reaches_the_result_of_explore(corridor: covmap.World, short_run: covmap.ExplorationResult) -> None:
    run = covmap.Exploration(corridor, covmap.Strategy.coverage(0.5), seed=3, max_steps=STEPS)
    assert not run.done and run.termination is None and run.steps == 0 and run.scans == 0
    assert run.map.grid == run.grid == short_run.grid
    np.testing.assert_array_equal(run.pose, short_run.start)
    # The start is the trajectory's first pose before the first step.
    np.testing.assert_array_equal(run.trajectory, [short_run.start])
    assert not run.map.observed().any()
    first = run.step()
    assert isinstance(first, covmap.Step) and first.index == 0 and first.scans >= 1
    assert first.path.ndim == 2 and first.path.shape[1] == 2 and first.goal.shape == (3,)
    np.testing.assert_array_equal(first.pose, run.pose)
    assert run.steps == 1 and run.map.observed().any()
    assert run.path_length_m == pytest.approx(first.travelled_m)
    partial = run.result()
    assert partial.termination is None and partial.steps == 1
    rest = list(run)
    assert [s.index for s in rest] == list(range(1, STEPS))
    # The first scan, at the start (taken by the first step before it decides),
    # is not counted among that step's scans today: see the report of issue 19.
    assert sum(s.scans for s in [first, *rest]) in (run.scans - 1, run.scans)
    assert run.done and run.termination == "limit" and run.step() is None
    assert run.uncertain_fraction == short_run.high_entropy_fraction
    np.testing.assert_array_equal(run.evaluation_cells, short_run.evaluation_cells)
    assert_same_run(run.result(), short_run)
    assert "limit" in repr(run) and repr(run.strategy) in repr(run)


@pytest.mark.parametrize("alpha", [0.2, 0.5])
def test_a_planner_with_its_defaults_makes_the_loops_choice(corridor: covmap.World, alpha: float) -> None:
    """The planner's defaults are the loop's settings: on the map the loop has
    built, from where the robot stands, covmap.Planner chooses the goal the
    decision-theoretic strategy drives to next (in the first steps, before
    the loop has ruled out any goal it failed to reach or that taught it
    nothing)."""
    run = covmap.Exploration(corridor, covmap.Strategy.coverage(alpha), seed=1, max_steps=12)
    ring = covmap.SonarRing()
    planner = covmap.Planner(alpha=alpha)
    agreed = 0
    assert run.step() is not None  # the first scans are taken by the first step
    while True:
        plan = planner.next_viewpoint(run.map, run.pose, ring.bearings, covmap.SonarModel())
        step = run.step()
        if step is None:
            break
        assert plan.pose is not None
        agreed += int(np.array_equal(plan.pose, step.goal))
        np.testing.assert_array_equal(plan.path[0], step.path[0])
    assert agreed == run.steps - 1 == 11, f"{agreed} of {run.steps - 1} goals"


def test_run_finishes_what_steps_began() -> None:
    whole = covmap.explore(room(), covmap.Strategy.counting(1), seed=2, resolution=0.1)
    run = covmap.Exploration(room(), covmap.Strategy.counting(1), seed=2, resolution=0.1)
    run.step()
    assert_same_run(run.run(), whole)
    assert run.done and run.run().steps == whole.steps


def test_the_occupancy_grid_pickles(short_run: covmap.ExplorationResult) -> None:
    grid = short_run.occupancy
    for back in (pickle.loads(pickle.dumps(grid)), copy.deepcopy(grid)):
        assert back.grid == grid.grid
        np.testing.assert_array_equal(back.log_odds(), grid.log_odds())
        np.testing.assert_array_equal(back.counts(), grid.counts())
        np.testing.assert_array_equal(back.observed(), grid.observed())
    other = covmap.OccupancyGrid(covmap.Grid(origin=(0, 0), resolution=0.1, shape=(3, 3)))
    with pytest.raises(covmap.InvalidValueError, match="lies on Grid"):
        other.__setstate__(grid.__getstate__())
    with pytest.raises(covmap.InvalidValueError, match="not a saved occupancy grid"):
        other.__setstate__(b'{"model": 1}')
    with pytest.raises(covmap.InvalidTypeError, match="bytes"):
        other.__setstate__("text")  # type: ignore[arg-type]
    assert not other.observed().any()


# -- bad input --------------------------------------------------------------


@pytest.mark.parametrize(
    ("options", "error", "match"),
    [
        ({"resolution": 0.0}, covmap.InvalidParameterError, "`resolution` = 0"),
        ({"resolution": -0.05}, covmap.InvalidParameterError, "`resolution` = -0.05"),
        ({"resolution": math.nan}, covmap.InvalidParameterError, "`resolution` = NaN"),
        ({"robot_radius_m": 0.0}, covmap.InvalidParameterError, "`robot_radius_m` = 0"),
        ({"robot_radius_m": -0.25}, covmap.InvalidParameterError, "`robot_radius_m` = -0.25"),
        ({"scan_spacing_m": -1.0}, covmap.InvalidParameterError, "`scan_spacing_m` = -1"),
        ({"candidate_stride_m": -0.5}, covmap.InvalidParameterError, "`candidate_stride_m` = -0.5"),
        ({"max_path_m": -10.0}, covmap.InvalidParameterError, "`max_path_m` = -10"),
        ({"max_steps": 0}, covmap.InvalidParameterError, "argument 'max_steps': 0 is out of range: expected an integer from 1 to 2\\*\\*64 - 1"),
        ({"max_steps": -1}, covmap.InvalidParameterError, "argument 'max_steps': -1 is out of range"),
        ({"epsilon": 0.0}, covmap.InvalidParameterError, "`epsilon` = 0"),
        ({"bins": 1}, covmap.InvalidParameterError, "argument 'bins': 1 is out of range: expected an integer from 2 to 256"),
        ({"seed": -1}, covmap.InvalidParameterError, "argument 'seed': -1 is out of range: expected an integer from 0 to 2\\*\\*64 - 1"),
        ({"start": (2.0, 1.0, 0.0)}, covmap.InvalidStartError, r"\(2, 1\).*overlaps an obstacle"),
        ({"start": (50.0, 1.0, 0.0)}, covmap.PoseOutsideMapError, "50"),
        ({"start": (math.nan, 1.0, 0.0)}, covmap.InvalidPoseError, "NaN"),
        ({"start": (1.0, 1.0)}, covmap.ArrayShapeError, "three numbers"),
        ({"sensor": covmap.SonarModel()}, covmap.InvalidTypeError, "SonarRing or a Laser"),
        ({"model": covmap.SonarRing()}, covmap.InvalidTypeError, "SonarModel or a LaserModel"),
        ({"seed": "zero"}, covmap.InvalidTypeError, "argument 'seed': expected an integer from 0 to 2\\*\\*64 - 1, got str 'zero'"),
    ],
)
def test_bad_input_is_refused_before_anything_runs(options: dict[str, Any], error: type, match: str) -> None:
    world, strategy = room(), covmap.Strategy.coverage()
    with pytest.raises(error, match=match) as raised:
        covmap.explore(world, strategy, **options)
    assert isinstance(raised.value, covmap.CovmapError)
    assert isinstance(raised.value, TypeError if issubclass(error, TypeError) else ValueError)
    with pytest.raises(error, match=match):
        covmap.Exploration(world, strategy, **options)


def test_a_strategy_must_be_a_strategy() -> None:
    for wrong in ("coverage", None, covmap.Planner()):
        with pytest.raises(covmap.InvalidTypeError, match="strategy must be a Strategy"):
            covmap.explore(room(), wrong)  # type: ignore[arg-type]
        with pytest.raises(covmap.InvalidTypeError, match="strategy must be a Strategy"):
            covmap.Exploration(room(), wrong)  # type: ignore[arg-type]


def test_a_world_the_robot_fits_nowhere_in_is_refused() -> None:
    # A solid block: nowhere on its grid keeps the robot's disc clear.
    block = covmap.World([[(0, 0), (0.5, 0), (0.5, 0.5), (0, 0.5)]])
    with pytest.raises(covmap.InvalidStartError, match="fits nowhere"):
        covmap.explore(block, covmap.Strategy.frontier(), robot_radius_m=2.0)


def test_readme_exploration_example_runs() -> None:
    import re
    from pathlib import Path

    readme = Path(__file__).resolve().parents[2] / "README.md"
    if not readme.is_file():
        pytest.skip("no README.md beside the package")
    blocks = re.findall(r"```python\n(.*?)```", readme.read_text(), flags=re.S)
    example = next(b for b in blocks if "covmap.explore(" in b)
    namespace: dict[str, Any] = {}
    exec(compile(example, str(readme), "exec"), namespace)
    result, run = namespace["result"], namespace["run"]
    assert result.termination == "limit" and result.steps == 10
    assert namespace["seen"].shape == result.grid.shape
    assert run.done and run.steps == 3
    assert pickle.loads(pickle.dumps(run.result())).steps == 3


def test_no_echo_readings_clear_their_whole_footprint_on_request(corridor: covmap.World) -> None:
    # The default occludes no-echo readings by the walls the map is certain
    # of; with occlude_no_echo=False every one clears its whole footprint,
    # the paper's reading: the same robot, the same readings, other maps.
    steps = 12
    occluded = covmap.explore(corridor, covmap.Strategy.coverage(0.5), seed=3, max_steps=steps)
    again = covmap.explore(corridor, covmap.Strategy.coverage(0.5), seed=3, max_steps=steps, occlude_no_echo=True)
    clearing = covmap.explore(corridor, covmap.Strategy.coverage(0.5), seed=3, max_steps=steps, occlude_no_echo=False)
    np.testing.assert_array_equal(occluded.map.histograms, again.map.histograms)
    assert not np.array_equal(occluded.map.histograms, clearing.map.histograms)
    first = covmap.Exploration(corridor, covmap.Strategy.coverage(0.5), seed=3, occlude_no_echo=False).step()
    assert first is not None
    with pytest.raises(TypeError, match="occlude_no_echo"):
        covmap.explore(corridor, covmap.Strategy.coverage(0.5), max_steps=1, occlude_no_echo="no")  # type: ignore[arg-type]
