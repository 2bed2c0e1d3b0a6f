"""Simulated sensors and the disc robot, as a user drives them."""

from __future__ import annotations

import math

import numpy as np
import pytest

import covmap

POSE = (2.0, 1.3, 0.0)


@pytest.fixture(scope="module")
def corridor() -> covmap.World:
    return covmap.World.builtin("corridor")


def wall_at_x(x: float, material: str = "wall") -> covmap.World:
    """A long wall whose face is the line ``x`` (y in [-10, 10])."""
    face = np.array([[x, -10.0], [x + 1.0, -10.0], [x + 1.0, 10.0], [x, 10.0]])
    return covmap.World([face], materials=[material])


def test_sonar_ring_defaults() -> None:
    ring = covmap.SonarRing()
    assert ring.bearings.dtype == np.float64 and ring.bearings.shape == (24,)
    np.testing.assert_allclose(np.diff(ring.bearings), math.radians(15.0))
    np.testing.assert_array_equal(ring.bearings, ring.bearings_rad)
    model = covmap.SonarModel()
    assert ring.opening_angle_rad == model.opening_angle_rad
    assert ring.max_range_m == model.max_range_m
    assert ring.rays_per_cone == 7
    assert ring.min_range_m == pytest.approx(0.15)
    assert ring.critical_angle_glass_rad == pytest.approx(math.radians(10.0))
    assert ring == covmap.SonarRing()
    assert ring != covmap.SonarRing(noise_std_m=0.0)


def test_sonar_ring_layouts() -> None:
    front = covmap.SonarRing.front_eight()
    np.testing.assert_allclose(np.degrees(front.bearings), [-90, -37.5, -22.5, -7.5, 7.5, 22.5, 37.5, 90])
    assert len(covmap.SonarRing.ring(8).bearings) == 8
    custom = covmap.SonarRing(bearings_rad=np.array([0.0, math.pi]), rays_per_cone=3)
    np.testing.assert_array_equal(custom.bearings, [0.0, math.pi])
    narrow = covmap.SonarModel(opening_angle_rad=0.1, max_range_m=3.0)
    matched = covmap.SonarRing().with_model(narrow)
    assert (matched.opening_angle_rad, matched.max_range_m) == (0.1, 3.0)


def test_quiet_sonar_reads_the_distance() -> None:
    ring = covmap.SonarRing(
        bearings_rad=[0.0],
        rays_per_cone=1,
        noise_std_m=0.0,
        noise_std_per_m=0.0,
        outlier_probability=0.0,
        multipath_probability=0.0,
    )
    ranges, bearings = ring.simulate(wall_at_x(2.0), (0.0, 0.0, 0.0), seed=3)
    assert ranges[0] == pytest.approx(2.0, abs=1e-12)
    np.testing.assert_array_equal(bearings, [0.0])
    # Glass echoes only near normal incidence: 30 degrees off is a specular miss.
    ranges, _ = ring.simulate(wall_at_x(2.0, "glass"), (0.0, 0.0, math.radians(30.0)), seed=3)
    assert ranges[0] == ring.max_range_m


@pytest.mark.parametrize("sensor", [covmap.SonarRing(), covmap.Laser()], ids=["sonar", "laser"])
def test_same_seed_same_scan(corridor: covmap.World, sensor: covmap.SonarRing | covmap.Laser) -> None:
    ranges, bearings = sensor.simulate(corridor, POSE, seed=5)
    again, _ = sensor.simulate(corridor, POSE, seed=5)
    other, _ = sensor.simulate(corridor, POSE, seed=6)
    assert ranges.dtype == np.float64 and ranges.shape == bearings.shape == sensor.bearings.shape
    np.testing.assert_array_equal(ranges, again)
    assert not np.array_equal(ranges, other)
    assert np.all((ranges > 0.0) & (ranges <= sensor.max_range_m))


@pytest.mark.parametrize("sensor", [covmap.SonarRing(), covmap.Laser()], ids=["sonar", "laser"])
def test_simulate_path_streams(corridor: covmap.World, sensor: covmap.SonarRing | covmap.Laser) -> None:
    poses = np.array([[2.0, 1.3, 0.0], [4.0, 1.2, 0.5], [6.0, 1.4, -1.0]])
    ranges = sensor.simulate_path(corridor, poses, seed=9)
    assert ranges.shape == (3, len(sensor.bearings)) and ranges.dtype == np.float64
    np.testing.assert_array_equal(ranges[0], sensor.simulate(corridor, poses[0], seed=9)[0])
    np.testing.assert_array_equal(ranges, sensor.simulate_path(corridor, poses, seed=9))
    assert not np.array_equal(ranges, sensor.simulate_path(corridor, poses, seed=10))


def test_scans_feed_the_coverage_map(corridor: covmap.World) -> None:
    grid = covmap.Grid.covering(corridor.bounds, resolution=0.05)
    cmap = covmap.CoverageMap(grid)
    ring = covmap.SonarRing()
    ranges, bearings = ring.simulate(corridor, POSE, seed=1)
    assert cmap.integrate(POSE, ranges, bearings, covmap.SonarModel()) > 0
    laser = covmap.Laser()
    ranges, bearings = laser.simulate(corridor, POSE, seed=1)
    assert cmap.integrate(POSE, ranges, bearings, covmap.LaserModel()) > 0
    # Straight ahead along the corridor's centre line the cells are now empty.
    row, col = grid.world_to_cell(4.0, 1.3)  # type: ignore[misc]
    assert cmap.ml()[row, col] == 0.0


def test_laser_layouts_and_readings() -> None:
    laser = covmap.Laser()
    assert len(laser.bearings) == 361
    assert laser.bearings[0] == pytest.approx(-math.pi / 2) and laser.bearings[-1] == pytest.approx(math.pi / 2)
    np.testing.assert_allclose(np.diff(covmap.Laser(180).bearings), math.pi / 179)
    np.testing.assert_allclose(np.diff(covmap.Laser(90, math.pi / 2).bearings), math.pi / 2 / 89)
    np.testing.assert_allclose(np.degrees(covmap.Laser.sick_180().bearings), np.arange(-90.0, 90.0))
    np.testing.assert_allclose(covmap.Laser.sick_361().bearings, laser.bearings, atol=1e-12)
    quiet = covmap.Laser(noise_std_m=0.0)
    ranges, bearings = quiet.simulate(wall_at_x(3.0), (0.0, 0.0, 0.0))
    with np.errstate(divide="ignore"):
        expected = np.where(np.cos(bearings) > 1e-9, 3.0 / np.cos(bearings), 30.0)
    # Beyond |y| = 10 the beam passes the wall's end.
    expected[np.abs(3.0 * np.tan(bearings)) > 10.0] = 30.0
    np.testing.assert_allclose(ranges, np.minimum(expected, 30.0), atol=1e-9)


@pytest.mark.parametrize(
    ("make", "cls"),
    [
        (lambda: covmap.SonarRing(noise_std_m=-0.1), covmap.InvalidParameterError),
        (lambda: covmap.SonarRing(rays_per_cone=0), covmap.InvalidParameterError),
        (lambda: covmap.SonarRing(rays_per_cone=-2), covmap.InvalidParameterError),
        (lambda: covmap.SonarRing(opening_angle_rad=math.pi), covmap.InvalidParameterError),
        (lambda: covmap.SonarRing(min_range_m=6.0), covmap.InvalidParameterError),
        (lambda: covmap.SonarRing(outlier_probability=1.5), covmap.InvalidParameterError),
        (lambda: covmap.SonarRing(bearings_rad=[]), covmap.InvalidParameterError),
        (lambda: covmap.SonarRing(bearings_rad=[0.0, math.nan]), covmap.InvalidValueError),
        (lambda: covmap.SonarRing(bearings_rad=np.zeros(3, dtype=np.float16)), covmap.ArrayDtypeError),
        (lambda: covmap.Laser(1), covmap.InvalidParameterError),
        (lambda: covmap.Laser(10, 0.0), covmap.InvalidParameterError),
        (lambda: covmap.Laser(max_range_m=-1.0), covmap.InvalidParameterError),
        (lambda: covmap.Laser(bearings_rad=[0.0, math.inf]), covmap.InvalidValueError),
    ],
)
def test_bad_sensor_parameters(make: object, cls: type[Exception]) -> None:
    with pytest.raises(cls) as info:
        make()  # type: ignore[operator]
    assert isinstance(info.value, covmap.CovmapError)


def test_laser_takes_beams_or_bearings_not_both() -> None:
    with pytest.raises(TypeError, match="not both"):
        covmap.Laser(10, bearings_rad=[0.0, 1.0])


@pytest.mark.parametrize("sensor", [covmap.SonarRing(), covmap.Laser()], ids=["sonar", "laser"])
def test_bad_poses_raise(corridor: covmap.World, sensor: covmap.SonarRing | covmap.Laser) -> None:
    with pytest.raises(covmap.InvalidPoseError) as info:
        sensor.simulate(corridor, (math.nan, 1.3, 0.0))
    assert isinstance(info.value, ValueError)
    with pytest.raises(covmap.InvalidPoseError):
        sensor.simulate_path(corridor, np.array([[2.0, 1.3, 0.0], [2.0, math.inf, 0.0]]))
    with pytest.raises(covmap.ArrayShapeError):
        sensor.simulate(corridor, (2.0, 1.3))
    with pytest.raises(covmap.ArrayShapeError):
        sensor.simulate_path(corridor, np.zeros((2, 2)))
    with pytest.raises(covmap.ArrayDtypeError):
        sensor.simulate_path(corridor, np.zeros((2, 3), dtype=np.float16))
    with pytest.raises(TypeError):
        sensor.simulate("corridor", POSE)  # type: ignore[arg-type]


def test_robot_collisions(corridor: covmap.World) -> None:
    robot = covmap.Robot(radius_m=0.25)
    assert robot.radius_m == 0.25
    assert covmap.Robot().radius_m == covmap.Planner().robot_radius_m
    assert not robot.collides(corridor, POSE)
    assert robot.collides(corridor, (2.0, 0.1))  # against the south wall
    assert robot.collides(corridor, (math.nan, 1.3, 0.0))
    # Driving into the west wall (inner face x = 0) stops 0.25 m short of it.
    assert robot.move_collides(corridor, (2.0, 1.3), (-1.0, 1.3))
    assert robot.free_travel(corridor, (2.0, 1.3), (-1.0, 1.3)) == pytest.approx(1.75, abs=1e-6)
    assert not robot.move_collides(corridor, (2.0, 1.3, 0.0), (5.0, 1.3, 0.0))
    gaps = robot.clearance(corridor, np.array([[2.0, 1.3], [0.5, 1.3]]))
    np.testing.assert_allclose(gaps, [1.3 - 0.25, 0.5 - 0.25], atol=1e-9)


def test_bad_robots_raise(corridor: covmap.World) -> None:
    with pytest.raises(covmap.InvalidParameterError):
        covmap.Robot(radius_m=0.0)
    with pytest.raises(covmap.ArrayShapeError):
        covmap.Robot().collides(corridor, (1.0,))
    with pytest.raises(covmap.ArrayShapeError):
        covmap.Robot().clearance(corridor, np.zeros((2, 3)))
