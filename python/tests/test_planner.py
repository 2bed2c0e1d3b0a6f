"""The planner (paper eq. 14) and the exploration state of a map."""

from __future__ import annotations

import math

import numpy as np
import pytest

import covmap

RING = np.linspace(0.0, 2 * math.pi, 24, endpoint=False)
SONAR = covmap.SonarModel()
POSE = (4.0, 4.0, 0.0)


@pytest.fixture
def room() -> covmap.CoverageMap:
    """A square room 4 m wide (8 m x 8 m map at 5 cm) seen three times from its centre."""
    cmap = covmap.CoverageMap(covmap.Grid(origin=(0.0, 0.0), resolution=0.05, shape=(160, 160)))
    ranges = 2.0 / np.maximum(np.abs(np.cos(RING)), np.abs(np.sin(RING)))
    for _ in range(3):
        cmap.integrate(POSE, ranges, RING, SONAR)
    return cmap


def cell_of(cmap: covmap.CoverageMap, x: float, y: float) -> tuple[int, int]:
    cell = cmap.grid.world_to_cell(x, y)
    assert cell is not None
    return cell


def test_defaults_are_readable() -> None:
    p = covmap.Planner()
    assert (p.alpha, p.robot_radius_m, p.candidate_stride_m, p.min_travel_m) == (0.5, 0.25, 0.5, 0.25)
    assert (p.min_gain_nats, p.blocked_coverage, p.unknown_entropy_fraction) == (None, 0.5, 0.95)
    # By default the loop's rule: what making one cell at the prior certain is worth.
    assert p.least_gain_nats(16) == pytest.approx(math.log(16) - 0.65)
    assert p.least_gain_nats(2) == 1.0
    assert covmap.Planner(min_gain_nats=0.5).least_gain_nats(16) == 0.5
    assert (p.unknown_is_free, p.epsilon, p.range_step_m, p.stop_coverage) == (False, 0.65, None, "ml")
    q = covmap.Planner(alpha=0.2, unknown_is_free=True, range_step_m=0.02, stop_coverage="mean")
    assert (q.alpha, q.unknown_is_free, q.range_step_m, q.stop_coverage) == (0.2, True, 0.02, "mean")
    assert "alpha=0.2" in repr(q)


@pytest.mark.parametrize(
    "kwargs",
    [
        {"alpha": 1.5},
        {"alpha": math.nan},
        {"candidate_stride_m": 0.0},
        {"robot_radius_m": -0.1},
        {"blocked_coverage": 1.0},
        {"epsilon": 0.0},
        {"range_step_m": -0.05},
        {"stop_coverage": "median"},
    ],
)
def test_bad_settings_raise(kwargs: dict[str, object]) -> None:
    with pytest.raises(covmap.InvalidParameterError) as info:
        covmap.Planner(**kwargs)  # type: ignore[arg-type]
    assert isinstance(info.value, ValueError)


def test_picks_a_reachable_free_candidate(room: covmap.CoverageMap) -> None:
    planner = covmap.Planner()
    before = room.histograms
    plan = planner.next_viewpoint(room, POSE, RING, SONAR)
    np.testing.assert_array_equal(room.histograms, before)
    c = plan.candidates
    m = len(c)
    assert m > 0
    assert c.poses.shape == (m, 3) and c.poses.dtype == np.float64
    assert c.gains.shape == c.costs.shape == c.utilities.shape == (m,)
    assert plan.chosen is not None and plan.pose is not None
    np.testing.assert_array_equal(plan.pose, c.poses[plan.chosen])
    assert plan.gain == c.gains[plan.chosen] and plan.cost == c.costs[plan.chosen]
    assert plan.chosen == int(np.argmax(c.utilities))
    free = planner.free_space(room)
    costs = planner.path_costs(room, POSE)
    assert free.shape == costs.shape == room.grid.shape and free.dtype == np.bool_
    for x, y, theta in c.poses:
        row, col = cell_of(room, x, y)
        assert free[row, col] and math.isfinite(costs[row, col])
        # Inside the room's walls, less the robot's radius.
        assert abs(x - 4.0) < 1.8 and abs(y - 4.0) < 1.8
        assert theta == POSE[2]
    np.testing.assert_allclose(c.costs, [costs[cell_of(room, x, y)] for x, y, _ in c.poses])
    # The path runs from the robot's cell to the goal's, in steps of one cell.
    path = plan.path
    assert path.ndim == 2 and path.shape[1] == 2
    assert cell_of(room, *path[0]) == cell_of(room, POSE[0], POSE[1])
    assert cell_of(room, *path[-1]) == cell_of(room, plan.pose[0], plan.pose[1])
    steps = np.hypot(*np.diff(path, axis=0).T)
    assert np.all(steps <= 0.05 * math.sqrt(2) + 1e-9)
    assert steps.sum() == pytest.approx(plan.cost)


def test_candidate_gains_are_the_expected_information_gain(room: covmap.CoverageMap) -> None:
    plan = covmap.Planner().next_viewpoint(room, POSE, RING, SONAR)
    gains = covmap.expected_information_gain(room, plan.candidates.poses, RING, SONAR)
    np.testing.assert_allclose(plan.candidates.gains, gains, rtol=1e-12)


def test_alpha_extremes(room: covmap.CoverageMap) -> None:
    near = covmap.Planner(alpha=0.0, min_travel_m=0.3).next_viewpoint(room, POSE, RING, SONAR)
    far = covmap.Planner(alpha=1.0, min_travel_m=0.3).next_viewpoint(room, POSE, RING, SONAR)
    c = near.candidates
    worth = c.gains > 1.0
    assert worth.sum() >= 2
    assert near.chosen is not None and far.chosen is not None
    assert c.costs[near.chosen] == c.costs[worth].min()
    assert np.all(c.costs[near.chosen] >= 0.3)
    assert far.candidates.gains[far.chosen] == c.gains[worth].max()
    assert far.candidates.gains[far.chosen] > c.gains[near.chosen]


def test_no_worthwhile_candidate(room: covmap.CoverageMap) -> None:
    plan = covmap.Planner(min_gain_nats=1e12).next_viewpoint(room, POSE, RING, SONAR)
    assert plan.pose is None and plan.chosen is None and plan.gain is None and plan.cost is None
    assert plan.path.shape == (0, 2)
    assert len(plan.candidates) > 0
    assert np.all(np.isneginf(plan.candidates.utilities))


def test_bad_poses_raise(room: covmap.CoverageMap) -> None:
    planner = covmap.Planner()
    with pytest.raises(covmap.InvalidPoseError):
        planner.next_viewpoint(room, (math.nan, 4.0, 0.0), RING, SONAR)
    with pytest.raises(covmap.PoseOutsideMapError):
        planner.next_viewpoint(room, (9.0, 4.0, 0.0), RING, SONAR)
    with pytest.raises(covmap.InvalidBearingError):
        planner.next_viewpoint(room, POSE, [0.0, math.inf], SONAR)
    with pytest.raises(covmap.PoseOutsideMapError):
        planner.status(room, (-1.0, 4.0, 0.0))
    with pytest.raises(covmap.ArrayShapeError):
        planner.path_costs(room, (4.0, 4.0))
    # A pose that is no sequence of numbers: a covmap error (and a TypeError).
    for bad in [("a", 4.0, 0.0), None, np.array(["4", "4", "0"])]:
        with pytest.raises(covmap.ArrayDtypeError) as info:
            planner.next_viewpoint(room, bad, RING, SONAR)  # type: ignore[arg-type]
        assert isinstance(info.value, covmap.CovmapError) and isinstance(info.value, TypeError)


def test_status_of_a_fresh_room(room: covmap.CoverageMap) -> None:
    status = covmap.Planner().status(room, POSE)
    # Reachable through unknown space: all but the walls' cells.
    assert 0.9 * 160 * 160 < status.reachable_cells < 160 * 160
    assert status.certain_cells < status.reachable_cells
    assert status.stagnated_cells == 0  # no history kept
    assert not status.done
    assert status == covmap.Planner().status(room, POSE)
    assert "reachable_cells=" in repr(status)
    # A map where every cell is certain is explored.
    grid = room.grid
    one_hot = np.zeros((*grid.shape, 16), dtype=np.float32)
    one_hot[..., 0] = 1.0
    certain = covmap.Planner().status(covmap.CoverageMap.from_histograms(grid, one_hot), POSE)
    assert certain.done and certain.certain_cells == certain.reachable_cells == grid.rows * grid.cols


def test_history_counts_measurements_and_stagnation() -> None:
    grid = covmap.Grid(origin=(0.0, 0.0), resolution=0.05, shape=(4, 40))
    cmap = covmap.CoverageMap(grid)
    laser = covmap.LaserModel()
    pose = (0.01, 0.1, 0.0)
    assert not cmap.tracks_history
    cmap.integrate(pose, [1.0], [0.0], laser)
    np.testing.assert_array_equal(cmap.measurements(), 0)
    cmap.track_history(True)
    assert cmap.tracks_history
    row, col = grid.world_to_cell(0.5, 0.1)  # type: ignore[misc]
    for k in range(5):
        cmap.integrate(pose, [1.0], [0.0], laser)
        measurements = cmap.measurements()
        assert measurements.dtype == np.uint32 and measurements.shape == (4, 40)
        assert measurements[row, col] == k + 1
        assert not cmap.stagnated()[row, col]
    # Many readings per scan: the cell's entropy settles.
    for _ in range(40):
        cmap.integrate(pose, [1.0] * 50, [0.0] * 50, laser)
    stagnated = cmap.stagnated()
    assert stagnated.dtype == np.bool_ and stagnated[row, col]
    far = grid.world_to_cell(1.9, 0.1)
    assert far is not None and cmap.measurements()[far] == 0 and not stagnated[far]
    cmap.track_history(False)
    assert not cmap.tracks_history and not cmap.stagnated().any()

