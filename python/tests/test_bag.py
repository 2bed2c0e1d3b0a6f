"""covmap.Log.from_bag on ROS 1 and ROS 2 bags that the tests write with
rosbags' own writers: LaserScan and Range topics, poses from odometry or tf
interpolated by timestamp, the mounting from the static transforms, a map
built from a bag, and bad bags refused with errors naming the file."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

import covmap
from bags import FORMATS, BagWriter, need_rosbags

pytestmark = pytest.mark.usefixtures("rosbags_installed")

FAN = {"angle_min": -0.5, "angle_increment": 0.25, "range_max": 8.0}
T0 = 1_700_000_000.0
"""A stamp of today's size, whose float64 seconds keep sub-microsecond steps."""


@pytest.fixture
def rosbags_installed() -> None:
    need_rosbags()


def drive(t_s: float) -> tuple[float, float, float]:
    """The robot's pose at ``t_s``: linear in time, so that linear
    interpolation between samples is exact."""
    dt = t_s - T0
    return (1.0 + 0.5 * dt, 2.0 + 0.2 * dt, 0.3 + 0.8 * dt)


SCAN_TIMES = [T0 + 0.05 + 0.1 * i for i in range(8)]
SAMPLE_TIMES = [T0 + 0.1 * i for i in range(10)]
MOUNT = [("base_link", "laser_mount", (0.2, 0.0, 0.0)), ("laser_mount", "laser", (0.0, 0.05, math.pi / 2))]
"""Two static steps: the laser at (0.2, 0.05) facing left."""


def scan_ranges(i: int) -> list[float]:
    return [1.0, math.inf, math.nan, 2.5 + 0.01 * i, 0.01]


def write_laser_bag(bag: BagWriter, *, odometry: bool = True, tf: bool = False, mount: bool = True) -> None:
    for t in SAMPLE_TIMES:
        if odometry:
            bag.write("/odom", bag.odometry(t, drive(t)), t)
        if tf:
            bag.write("/tf", bag.tf(t, ("odom", "base_link", drive(t))), t)
    if tf:
        bag.write("/tf_static", bag.tf(T0, ("map", "odom", (1.0, -1.0, math.pi / 2))), T0)
    if mount:
        bag.write("/tf_static", bag.tf(T0, *MOUNT), T0)
    for i, t in enumerate(SCAN_TIMES):
        bag.write("/scan", bag.laser_scan(t, "laser", scan_ranges(i), **FAN), t + 0.01)


@pytest.mark.parametrize("bag_format", FORMATS)
def test_laser_scans_with_odometry_and_a_static_mounting(tmp_path: Path, bag_format: str) -> None:
    with BagWriter(tmp_path, "drive", bag_format) as bag:
        write_laser_bag(bag)
    log = covmap.Log.from_bag(bag.path, odom_topic="/odom")
    assert len(log) == 8 and log.beams == 5 and log.max_range_m == 8.0
    np.testing.assert_allclose(log.timestamps, SCAN_TIMES, rtol=0, atol=1e-6)
    np.testing.assert_allclose(log.poses, [drive(t) for t in SCAN_TIMES], atol=1e-6)
    np.testing.assert_allclose(log.bearings, [-0.5, -0.25, 0.0, 0.25, 0.5])
    ranges = log.ranges
    np.testing.assert_allclose(ranges[:, 0], 1.0)
    np.testing.assert_allclose(ranges[:, 1], 8.0)  # +inf: no echo
    assert np.isnan(ranges[:, 2]).all() and np.isnan(ranges[:, 4]).all()  # NaN, below range_min: dropped
    np.testing.assert_allclose(ranges[:, 3], [2.5 + 0.01 * i for i in range(8)], rtol=1e-6)
    np.testing.assert_allclose(log.sensor_offset, (0.2, 0.05, math.pi / 2), atol=1e-12)
    assert covmap.Log.from_bag(bag.path, odom_topic="/odom", max_range_m=3.0).max_range_m == 3.0


@pytest.mark.parametrize("bag_format", FORMATS)
def test_poses_from_tf_compose_the_tree_and_stop_at_the_fixed_frame(tmp_path: Path, bag_format: str) -> None:
    with BagWriter(tmp_path, "tf", bag_format) as bag:
        write_laser_bag(bag, odometry=False, tf=True)
    in_odom = np.array([drive(t) for t in SCAN_TIMES])
    log = covmap.Log.from_bag(bag.path, fixed_frame="odom")
    np.testing.assert_allclose(log.poses, in_odom, atol=1e-6)
    in_map = covmap.Log.from_bag(bag.path).poses  # the tree's root: map
    # map -> odom: (1, -1), a quarter turn left.
    np.testing.assert_allclose(in_map[:, 0], 1.0 - in_odom[:, 1], atol=1e-6)
    np.testing.assert_allclose(in_map[:, 1], -1.0 + in_odom[:, 0], atol=1e-6)
    np.testing.assert_allclose(in_map[:, 2], in_odom[:, 2] + math.pi / 2, atol=1e-6)
    with pytest.raises(covmap.FileFormatError, match="not at fixed_frame world"):
        covmap.Log.from_bag(bag.path, fixed_frame="world")


@pytest.mark.parametrize("bag_format", FORMATS)
def test_range_topics_read_one_sonar_a_log_with_its_own_mounting(tmp_path: Path, bag_format: str) -> None:
    sonars = {"front": (0.1, 0.0, 0.0), "left": (0.0, 0.1, math.pi / 2)}
    readings = [1.5, math.inf, -math.inf, 0.05, 2.0]
    with BagWriter(tmp_path, "sonar", bag_format) as bag:
        bag.write("/tf_static", bag.tf(T0, *(("base_link", f"sonar_{n}", p) for n, p in sonars.items())), T0)
        for t in SAMPLE_TIMES:
            bag.write("/odom", bag.odometry(t, drive(t)), t)
        for i, t in enumerate(SCAN_TIMES[:5]):
            for name in sonars:
                bag.write(f"/sonar/{name}", bag.range(t, f"sonar_{name}", readings[i]), t)
    with pytest.raises(covmap.FileFormatError, match="2 LaserScan or Range topics"):
        covmap.Log.from_bag(bag.path, odom_topic="/odom")
    for name, mounting in sonars.items():
        log = covmap.Log.from_bag(bag.path, topic=f"/sonar/{name}", odom_topic="/odom")
        assert len(log) == 5 and log.beams == 1 and log.max_range_m == 5.0
        np.testing.assert_array_equal(log.bearings, [0.0])
        np.testing.assert_allclose(log.sensor_offset, mounting, atol=1e-12)
        ranges = log.ranges[:, 0]
        np.testing.assert_allclose(ranges[[0, 1, 4]], [1.5, 5.0, 2.0])  # +inf: no echo
        assert np.isnan(ranges[[2, 3]]).all()  # -inf and below min_range: dropped
        np.testing.assert_allclose(log.poses, [drive(t) for t in SCAN_TIMES[:5]], atol=1e-6)


@pytest.mark.parametrize("bag_format", FORMATS)
def test_a_map_from_a_bag_is_the_map_of_its_scans(tmp_path: Path, bag_format: str) -> None:
    world = covmap.World.builtin("corridor")
    laser = covmap.Laser(beams=91, fov_rad=math.pi)
    poses = np.array([[1.0 + 0.25 * i, 1.3, 0.05 * i] for i in range(12)])
    recorded = laser.record(world, poses, seed=5)
    step = float(recorded.bearings[1] - recorded.bearings[0])
    with BagWriter(tmp_path, "corridor", bag_format) as bag:
        for i, (pose, ranges) in enumerate(zip(poses, recorded.ranges)):
            t = T0 + 0.2 * i
            bag.write("/odom", bag.odometry(t, tuple(pose)), t)
            scan = bag.laser_scan(
                t, "base_link", ranges, angle_min=float(recorded.bearings[0]), angle_increment=step, range_max=30.0
            )
            bag.write("/scan", scan, t)
    log = covmap.Log.from_bag(bag.path, odom_topic="/odom")
    np.testing.assert_allclose(log.poses, poses, atol=1e-9)
    np.testing.assert_allclose(log.ranges, recorded.ranges, rtol=1e-6)  # float32 in the bag
    assert log.sensor_offset == (0.0, 0.0, 0.0)
    grid = covmap.Grid.covering(log.extent(10.0) or (0, 0, 1, 1), resolution=0.1)
    from_bag, from_log = covmap.CoverageMap(grid), covmap.CoverageMap(grid)
    from_bag.integrate_log(log, covmap.LaserModel())
    from_log.integrate_log(recorded, covmap.LaserModel())
    assert (from_bag.ml() == from_log.ml()).mean() > 0.99
    assert (from_bag.ml() > 0.5).sum() > 50  # the corridor's walls


def test_bad_bags_are_typed_errors_naming_the_file(tmp_path: Path) -> None:
    with BagWriter(tmp_path, "drive", "ros2") as bag:
        write_laser_bag(bag)
    path = str(bag.path)
    cases = [
        ({"topic": "/nope", "odom_topic": "/odom"}, "topic /nope", "no such topic"),
        ({"topic": "/odom", "odom_topic": "/odom"}, "topic /odom", "holds nav_msgs/msg/Odometry messages"),
        ({"odom_topic": "/scan"}, "topic /scan", "not nav_msgs/msg/Odometry"),
        ({}, "/tf", "no transform of the robot's frame base_link"),
        ({"odom_topic": "/odom", "base_frame": "chassis"}, "the odometry", "not base_frame chassis"),
    ]
    for kwargs, place, reason in cases:
        with pytest.raises(covmap.FileFormatError, match=reason) as caught:
            covmap.Log.from_bag(bag.path, **kwargs)  # type: ignore[arg-type]
        assert caught.value.filename == path and caught.value.place == place, kwargs
        assert str(caught.value).startswith(path)
    with BagWriter(tmp_path, "unmounted", "ros1") as bag:
        write_laser_bag(bag, mount=False)
    with pytest.raises(covmap.FileFormatError, match="no static transform from the robot's frame base_link"):
        covmap.Log.from_bag(bag.path, odom_topic="/odom")
    with BagWriter(tmp_path, "silent-odometry", "ros2") as bag:
        bag.writer.add_connection("/odom", "nav_msgs/msg/Odometry", typestore=bag.store)
        bag.write("/scan", bag.laser_scan(T0, "base_link", scan_ranges(0), **FAN), T0)
    with pytest.raises(covmap.FileFormatError, match="holds no messages") as silent:
        covmap.Log.from_bag(bag.path, odom_topic="/odom")
    assert silent.value.place == "topic /odom"
    with pytest.raises(covmap.FileIOError) as missing:
        covmap.Log.from_bag(tmp_path / "absent.bag")
    assert missing.value.filename == str(tmp_path / "absent.bag")


@pytest.mark.parametrize("bag_format", FORMATS)
def test_truncated_and_foreign_files_are_not_readable_bags(tmp_path: Path, bag_format: str) -> None:
    with BagWriter(tmp_path, "drive", bag_format) as bag:
        write_laser_bag(bag)
    data = bag.path if bag_format == "ros1" else next(bag.path.glob("*.db3"))
    data.write_bytes(data.read_bytes()[: data.stat().st_size // 2])
    with pytest.raises(covmap.FileFormatError, match="not a readable bag") as caught:
        covmap.Log.from_bag(bag.path, odom_topic="/odom")
    assert caught.value.filename == str(bag.path) and caught.value.place == "the bag"
    foreign = tmp_path / "foreign.bag"
    foreign.write_bytes(b"FLASER 3 1 2 3 0 0 0 0 0 0 1 host 1\n")
    with pytest.raises(covmap.FileFormatError, match="not a readable bag"):
        covmap.Log.from_bag(foreign)


def test_without_rosbags_the_error_says_what_to_install(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    monkeypatch.setitem(sys.modules, "rosbags.highlevel", None)
    with pytest.raises(covmap.MissingDependencyError, match=r"covmap\[rosbags\]"):
        covmap.Log.from_bag(tmp_path)
