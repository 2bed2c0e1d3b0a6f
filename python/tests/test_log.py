"""covmap.Log as a user builds and reads one: from arrays, CARMEN and sonar
files, ROS LaserScan conventions, simulated sensors; integrate_log on the
maps; errors that name the file, the line and the scan."""

from __future__ import annotations

import gzip
import math
import pickle
from pathlib import Path
from typing import Callable

import numpy as np
import pytest

import covmap

SONAR_BEARINGS_DEG = [-90, -37.5, -22.5, -7.5, 7.5, 22.5, 37.5, 90]


def small_log(n: int = 4) -> covmap.Log:
    poses = np.array([[1.0 + 0.2 * i, 1.5, 0.1 * i] for i in range(n)])
    ranges = np.array([[0.5 + 0.1 * ((i + k) % 5) for k in range(3)] for i in range(n)])
    return covmap.Log(poses, ranges, np.array([-0.3, 0.0, 0.3]), max_range_m=2.0)


def test_arrays_shapes_and_slices() -> None:
    log = small_log(5)
    assert len(log) == 5 and log.beams == 3
    assert log.poses.shape == (5, 3) and log.ranges.shape == (5, 3)
    assert log.bearings.shape == (3,) and log.timestamps.tolist() == [0, 1, 2, 3, 4]
    part = log[1:3]
    assert len(part) == 2
    np.testing.assert_array_equal(part.ranges, log.ranges[1:3])
    np.testing.assert_array_equal(log[-2:].poses, log.poses[-2:])
    assert len(log[4:1]) == 0
    with pytest.raises(covmap.InvalidValueError):
        log[::2]
    with pytest.raises(TypeError):
        log[0]  # type: ignore[call-overload]
    x0, y0, x1, y1 = log.extent(0.0) or (0, 0, 0, 0)
    assert (x0, x1) == (1.0, pytest.approx(1.8)) and y0 == y1 == 1.5
    far = log.extent(math.inf)
    assert far is not None and far[2] > 2.0
    assert log[0:0].extent(1.0) is None


def test_bad_arrays_are_typed_errors() -> None:
    poses = np.zeros((2, 3))
    b = np.array([0.0, 0.5])
    with pytest.raises(covmap.InvalidRangeError, match="scan 1"):
        covmap.Log(poses, np.array([[1.0, 1.0], [1.0, np.nan]]), b, max_range_m=5.0)
    with pytest.raises(covmap.InvalidRangeError, match="scan 0"):
        covmap.Log(poses, np.array([[1.0, -1.0], [1.0, 1.0]]), b, max_range_m=5.0)
    with pytest.raises(covmap.ArrayShapeError):
        covmap.Log(poses, np.ones((3, 2)), b, max_range_m=5.0)
    with pytest.raises(covmap.LengthMismatchError):
        covmap.Log(poses, np.ones((2, 3)), b, max_range_m=5.0)
    with pytest.raises(covmap.ArrayDtypeError):
        covmap.Log(poses, np.ones((2, 2), dtype=np.int64), b, max_range_m=5.0)
    with pytest.raises(covmap.InvalidParameterError):
        covmap.Log(poses, np.ones((2, 2)), b, max_range_m=0.0)


def test_laser_scans_follow_rep_117() -> None:
    ranges = np.array([[np.inf, 2.0, np.nan, -np.inf, 0.01, 12.0]], dtype=np.float32)
    log = covmap.Log.from_laser_scans(
        np.zeros((1, 3)), ranges, angle_min=-0.5, angle_increment=0.2, range_min=0.1, range_max=10.0
    )
    r = log.ranges[0]
    assert r[0] == 10.0 and r[1] == 2.0 and r[5] == 10.0  # no echo: the maximum range
    assert np.isnan(r[2:5]).all()  # NaN, -inf, below range_min: dropped
    np.testing.assert_allclose(log.bearings, -0.5 + 0.2 * np.arange(6))
    assert log.max_range_m == 10.0
    with pytest.raises(covmap.InvalidParameterError, match="range_max"):
        covmap.Log.from_laser_scans(
            np.zeros((1, 3)), ranges, angle_min=0, angle_increment=0.1, range_min=1, range_max=0.5
        )


def test_integrate_takes_float32_as_laserscan_hands_it() -> None:
    grid = covmap.Grid(origin=(0.0, 0.0), resolution=0.05, shape=(40, 40))
    a, b = covmap.CoverageMap(grid), covmap.CoverageMap(grid)
    ranges = np.array([0.75, 0.5], dtype=np.float32)
    bearings = np.array([0.0, 0.25], dtype=np.float32)
    a.integrate((1.0, 1.0, 0.0), ranges, bearings, covmap.LaserModel())
    b.integrate((1.0, 1.0, 0.0), ranges.astype(np.float64), bearings.astype(np.float64), covmap.LaserModel())
    np.testing.assert_array_equal(a.histograms, b.histograms)
    with pytest.raises(covmap.InvalidRangeError):
        a.integrate((1.0, 1.0, 0.0), np.array([np.nan], dtype=np.float32), [0.0], covmap.LaserModel())


def test_integrate_log_equals_scan_by_scan_and_a_bad_scan_changes_nothing() -> None:
    grid = covmap.Grid(origin=(0.0, 0.0), resolution=0.05, shape=(60, 60))
    log = small_log(6)
    model = covmap.SonarModel()
    whole, by_scan = covmap.CoverageMap(grid), covmap.CoverageMap(grid)
    seen: list[tuple[int, int]] = []
    whole.integrate_log(log, model, progress=lambda done, total: seen.append((done, total)))
    assert seen[-1] == (6, 6)
    assert (log.ranges < log.max_range_m).all()  # echoes only: as integrate takes them
    for pose, ranges in zip(log.poses, log.ranges):
        by_scan.integrate(pose, ranges, log.bearings, model)
    np.testing.assert_array_equal(whole.histograms, by_scan.histograms)

    poses = log.poses.copy()
    poses[4, 0] = 50.0  # outside the 3 x 3 m map
    bad = covmap.Log(poses, log.ranges, log.bearings, max_range_m=2.0)
    before = whole.histograms.copy()
    with pytest.raises(covmap.PoseOutsideMapError, match="scan 4"):
        whole.integrate_log(bad, model)
    np.testing.assert_array_equal(whole.histograms, before)
    occupancy = covmap.OccupancyGrid(grid)
    with pytest.raises(covmap.PoseOutsideMapError):
        occupancy.integrate_log(bad, model)
    assert (occupancy.counts() == 0).all()
    assert occupancy.integrate_log(log, model, progress=False) == 6
    assert occupancy.counts().sum() > 0
    with pytest.raises(TypeError):
        occupancy.integrate_log(log, model, progress="yes")  # type: ignore[arg-type]


def test_a_progress_callable_that_raises_leaves_the_maps_as_they_were() -> None:
    grid = covmap.Grid(origin=(0.0, 0.0), resolution=0.05, shape=(60, 60))
    log = small_log(6)
    model = covmap.SonarModel()

    def fails(done: int, total: int) -> None:
        if done >= 2:
            raise KeyError("stop")

    coverage, occupancy = covmap.CoverageMap(grid), covmap.OccupancyGrid(grid)
    coverage.integrate_log(small_log(2), model)
    occupancy.integrate_log(small_log(2), model)
    before = coverage.histograms.copy(), occupancy.log_odds().copy(), occupancy.counts().copy()
    with pytest.raises(KeyError, match="stop"):
        coverage.integrate_log(log, model, progress=fails)
    with pytest.raises(KeyError, match="stop"):
        occupancy.integrate_log(log, model, progress=fails)
    np.testing.assert_array_equal(coverage.histograms, before[0])
    np.testing.assert_array_equal(occupancy.log_odds(), before[1])
    np.testing.assert_array_equal(occupancy.counts(), before[2])
    # Without an error the copy takes the map's place: the same as no display.
    plain = covmap.CoverageMap(grid)
    plain.integrate_log(small_log(2), model)
    assert coverage.integrate_log(log, model, progress=lambda done, total: None) == plain.integrate_log(log, model)
    np.testing.assert_array_equal(coverage.histograms, plain.histograms)


def test_the_sensor_offset_moves_every_scan() -> None:
    grid = covmap.Grid(origin=(0.0, 0.0), resolution=0.05, shape=(60, 60))
    log = small_log(3)
    moved = log.with_sensor_offset((0.3, 0.0, 0.0))
    assert moved.sensor_offset == (0.3, 0.0, 0.0)
    shifted_poses = log.poses.copy()
    shifted_poses[:, 0] += 0.3 * np.cos(shifted_poses[:, 2])
    shifted_poses[:, 1] += 0.3 * np.sin(shifted_poses[:, 2])
    same = covmap.Log(shifted_poses, log.ranges, log.bearings, max_range_m=2.0)
    a, b = covmap.CoverageMap(grid), covmap.CoverageMap(grid)
    a.integrate_log(moved, covmap.LaserModel())
    b.integrate_log(same, covmap.LaserModel())
    np.testing.assert_allclose(a.histograms, b.histograms, atol=1e-6)


def test_logs_pickle() -> None:
    log = small_log(3).with_sensor_offset((0.1, 0.2, 0.3))
    back = pickle.loads(pickle.dumps(log))
    np.testing.assert_array_equal(back.ranges, log.ranges)
    np.testing.assert_array_equal(back.poses, log.poses)
    assert back.sensor_offset == log.sensor_offset and back.max_range_m == log.max_range_m


def test_simulated_sensors_record_logs() -> None:
    world = covmap.World.builtin("corridor")
    poses = np.array([[1.0 + 0.3 * i, 1.3, 0.0] for i in range(4)])
    for sensor in (covmap.Laser(), covmap.SonarRing()):
        log = sensor.record(world, poses, seed=3)
        np.testing.assert_array_equal(log.ranges, sensor.simulate_path(world, poses, seed=3))
        np.testing.assert_array_equal(log.bearings, sensor.bearings)
        assert log.max_range_m == sensor.max_range_m


def carmen_flaser(path: Path) -> list[list[float]]:
    """Every FLASER line of a CARMEN log, split by hand: n, ranges, pose, ..."""
    with gzip.open(path, "rt") as f:
        return [[float(w) for w in line.split()[1:-2]] for line in f if line.startswith("FLASER ")]


@pytest.mark.parametrize(
    "name,scans,beams",
    [("intel", 910, 180), ("seattle", 241, 361), ("aces", 440, 180), ("freiburg-079", 4791, 360)],
)
def test_carmen_logs_read_as_split_by_hand(
    shared_data: Callable[[str], Path], name: str, scans: int, beams: int
) -> None:
    path = shared_data(f"carmen/{name}-corrected.log.gz")
    log = covmap.Log.from_carmen(path)
    rows = carmen_flaser(path)
    assert len(log) == len(rows) == scans and log.beams == beams
    ranges = np.array([r[1 : 1 + beams] for r in rows])
    poses = np.array([r[1 + beams : 4 + beams] for r in rows])
    np.testing.assert_array_equal(log.ranges, ranges)
    np.testing.assert_array_equal(log.poses, poses)
    np.testing.assert_allclose(np.degrees(log.bearings[[0, -1]]), [-90, -90 + (beams - 1) * 180 / (beams - beams % 2)])


def test_sonar_ring_reads_as_split_by_hand(shared_data: Callable[[str], Path]) -> None:
    poses_path, meas_path = shared_data("sonar-8ring/poses.txt"), shared_data("sonar-8ring/measurement.txt")
    # The data set's units: millimetres, tenths of a degree.
    units = {"bearings_deg": SONAR_BEARINGS_DEG, "length_unit_m": 0.001, "angle_unit_rad": math.pi / 1800}
    log = covmap.Log.from_sonar_text(poses_path, meas_path, **units, max_range_m=5.0)
    p = np.loadtxt(poses_path)
    m = np.loadtxt(meas_path)
    assert len(log) == len(p) == 413
    np.testing.assert_allclose(log.poses, np.column_stack([p[:, 1:3] / 1000, np.radians(p[:, 3] / 10)]))
    np.testing.assert_allclose(log.ranges, m[:, 1:] / 1000)
    np.testing.assert_array_equal(log.timestamps, p[:, 0])
    # The data set's own description: 5110 is no echo, readings below
    # 170 mm are not valid.
    described = covmap.Log.from_sonar_text(
        poses_path, meas_path, **units, min_range_m=0.17, max_range_m=5.0, no_echo=5110
    )
    raw = m[:, 1:]
    expected = np.where(raw == 5110, 5.0, np.where(raw < 170, np.nan, raw / 1000))
    np.testing.assert_allclose(described.ranges, expected)
    assert np.isnan(described.ranges).sum() == (raw < 170).sum()
    # No reading of this data set is below 170 mm: a higher bound shows the
    # readings below it dropped (NaN), and only those.
    bounded = covmap.Log.from_sonar_text(poses_path, meas_path, **units, min_range_m=0.5, max_range_m=5.0, no_echo=5110)
    np.testing.assert_array_equal(np.isnan(bounded.ranges), raw < 500)
    assert (raw < 500).sum() > 0
    with pytest.raises(covmap.InvalidParameterError, match="min_range_m"):
        covmap.Log.from_sonar_text(poses_path, meas_path, bearings_deg=[0.0] * 8, min_range_m=6.0, max_range_m=5.0)


def test_malformed_files_name_the_file_and_line(tmp_path: Path) -> None:
    bad = tmp_path / "bad.log"
    bad.write_text("FLASER 2 1 2 0 0 0 0 0 0 1.0 h 1\nFLASER 2 1 x 0 0 0 0 0 0 1.0 h 1\n")
    with pytest.raises(covmap.FileFormatError, match="bad.log:2") as caught:
        covmap.Log.from_carmen(bad)
    assert caught.value.place == "line 2" and caught.value.filename == str(bad)
    with pytest.raises(covmap.FileIOError):
        covmap.Log.from_carmen(tmp_path / "absent.log")
    zipped = tmp_path / "cut.log.gz"
    text = "".join(f"FLASER 2 {i % 97} {i % 89} {i} 0 0 0 0 0 {i}.5 h 1\n" for i in range(2000))
    whole = gzip.compress(text.encode())
    zipped.write_bytes(whole[: len(whole) // 2])
    with pytest.raises(covmap.FileFormatError, match="cut.log.gz"):
        covmap.Log.from_carmen(zipped)
    poses = tmp_path / "p.txt"
    meas = tmp_path / "m.txt"
    poses.write_text("1 0 0 0\n2 0 0 0\n")
    meas.write_text("1 100 200\n3 100 200\n")
    with pytest.raises(covmap.FileFormatError, match="m.txt:2"):
        covmap.Log.from_sonar_text(poses, meas, bearings_deg=[0, 90], max_range_m=5.0)


def test_the_rear_laser_reads_rlaser_lines_with_their_own_poses(tmp_path: Path) -> None:
    path = tmp_path / "two-lasers.log"
    path.write_text(
        "PARAM robot_rear_laser_max 7.5 h 0\n"
        "FLASER 3 1 2 3 1.2 2.0 0.5 1 2 0.5 4.0 h 4.0\n"
        "RLASER 2 4 5 0.7 2.0 3.6 1 2 0.5 4.1 h 4.1\n"
    )
    front = covmap.Log.from_carmen(path)
    rear = covmap.Log.from_carmen(path, laser="rear")
    assert (len(front), front.beams, len(rear), rear.beams) == (1, 3, 1, 2)
    np.testing.assert_array_equal(rear.poses, [[0.7, 2.0, 3.6]])
    np.testing.assert_array_equal(rear.ranges, [[4.0, 5.0]])
    assert rear.max_range_m == 7.5 and rear.timestamps.tolist() == [4.1]
    with pytest.raises(covmap.InvalidParameterError, match="laser"):
        covmap.Log.from_carmen(path, laser="side")  # type: ignore[arg-type]
