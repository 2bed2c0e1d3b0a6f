"""``covmap map`` as a user runs it: a log in, the map files out."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Callable

import numpy as np
import pytest

import covmap
from bags import FORMATS, BagWriter, need_rosbags
from cli_helpers import PNG_SIGNATURE, run_cli


def square_room_log(path: Path) -> None:
    """A CARMEN log of a robot turning in the middle of a 6 x 6 m room:
    FLASER scans of 181 beams, the ranges to the walls worked out here."""
    lines = ["# a square room", "PARAM robot_frontlaser_offset 0.0 nohost 0"]
    for i in range(12):
        theta = i * math.pi / 6
        ranges = []
        for k in range(181):
            a = theta - math.pi / 2 + math.radians(k)
            # Walls at x = +-3 and y = +-3 around the robot at the origin.
            r = min(3 / abs(math.cos(a)) if math.cos(a) else math.inf, 3 / abs(math.sin(a)) if math.sin(a) else math.inf)
            ranges.append(f"{r:.3f}")
        lines.append(f"FLASER 181 {' '.join(ranges)} 0 0 {theta:.6f} 0 0 {theta:.6f} {i * 0.1:.1f} host {i * 0.1:.1f}")
    path.write_text("\n".join(lines) + "\n")


def test_a_carmen_log_becomes_its_map_files(tmp_path: Path) -> None:
    log = tmp_path / "room.log"
    square_room_log(log)
    out = tmp_path / "out"
    result = run_cli("map", str(log), "--resolution", "0.1", "--max-range", "20", "--out", str(out))
    assert result.returncode == 0, result.stdout + result.stderr
    assert "12 of 181 beams" in result.stdout
    names = sorted(p.name for p in out.iterdir())
    assert names == ["coverage.npz", "map.pgm", "map.yaml", "maps.png", "occupancy.pgm", "occupancy.yaml"]
    assert (out / "maps.png").read_bytes().startswith(PNG_SIGNATURE)
    cmap = covmap.CoverageMap.load(out / "coverage.npz")
    assert cmap.grid.resolution == 0.1
    # The walls read back from the map_server pair, where the room's are
    # (among the cells the map saw: the unknown ones read back as obstacles).
    world = covmap.World.from_file(out / "map.yaml")
    grid = cmap.grid
    seen = cmap.ros_occupancy() != -1
    assert (world.coverage(grid) > 0.5)[~seen].mean() > 0.95
    rows, cols = np.nonzero((world.coverage(grid) > 0.5) & seen)
    (x0, y0, _, _) = grid.bounds
    xs = x0 + (cols + 0.5) * grid.resolution
    ys = y0 + (rows + 0.5) * grid.resolution
    assert len(xs) > 100  # the four 6 m walls, 0.1 m cells
    on_a_wall = (np.abs(np.abs(xs) - 3.0) < 0.25) | (np.abs(np.abs(ys) - 3.0) < 0.25)
    assert on_a_wall.mean() > 0.95, on_a_wall.mean()


def test_a_malformed_log_is_an_error_naming_its_line(tmp_path: Path) -> None:
    log = tmp_path / "bad.log"
    log.write_text("FLASER 2 1 2 0 0 0 0 0 0 1.0 h 1\nFLASER 2 1 oops 0 0 0 0 0 0 1.0 h 1\n")
    result = run_cli("map", str(log), "--out", str(tmp_path / "out"))
    assert result.returncode == 2
    assert "bad.log:2" in result.stderr and "Traceback" not in result.stderr


def test_the_intel_log_maps(tmp_path: Path, shared_data: Callable[[str], Path]) -> None:
    log = shared_data("carmen/intel-corrected.log.gz")
    result = run_cli("map", str(log), "--out", str(tmp_path))
    assert result.returncode == 0, result.stdout + result.stderr
    assert "910 of 180 beams, max range 81.83 m" in result.stdout
    agreement = float(result.stdout.split("agreement")[1].split()[0])
    assert agreement > 0.95


def test_the_sonar_ring_maps(tmp_path: Path, shared_data: Callable[[str], Path]) -> None:
    poses, meas = shared_data("sonar-8ring/poses.txt"), shared_data("sonar-8ring/measurement.txt")
    result = run_cli("map", str(poses), "--measurements", str(meas), "--resolution", "0.1", "--out", str(tmp_path))
    assert result.returncode == 0, result.stdout + result.stderr
    assert "413 of 8 beams, max range 5 m, sonar model" in result.stdout


@pytest.mark.parametrize("bag_format", FORMATS)
def test_a_bag_maps_as_the_same_scans_in_a_carmen_log_do(tmp_path: Path, bag_format: str) -> None:
    need_rosbags()
    log = tmp_path / "room.log"
    square_room_log(log)
    carmen = covmap.Log.from_carmen(log, max_range_m=20.0)
    t0 = 1_700_000_000.0
    fan = {"angle_min": float(carmen.bearings[0]), "angle_increment": math.pi / 180, "range_max": 20.0}
    with BagWriter(tmp_path, "room", bag_format) as bag:
        for t, pose, ranges in zip(carmen.timestamps, carmen.poses, carmen.ranges):
            bag.write("/odom", bag.odometry(t0 + t, tuple(pose)), t0 + t)
            bag.write("/scan", bag.laser_scan(t0 + t, "base_link", ranges, **fan), t0 + t)
    common = ("--resolution", "0.1", "--max-range", "20")
    result = run_cli("map", str(log), *common, "--out", str(tmp_path / "carmen"))
    assert result.returncode == 0, result.stdout + result.stderr
    result = run_cli("map", str(bag.path), "--odom-topic", "/odom", *common, "--out", str(tmp_path / "bag"))
    assert result.returncode == 0, result.stdout + result.stderr
    assert "(rosbag)" in result.stdout and "12 of 181 beams" in result.stdout
    from_carmen = covmap.CoverageMap.load(tmp_path / "carmen" / "coverage.npz")
    from_bag = covmap.CoverageMap.load(tmp_path / "bag" / "coverage.npz")
    assert from_bag.grid.shape == from_carmen.grid.shape  # the bounds up to float32 ranges
    assert from_bag.grid.bounds == pytest.approx(from_carmen.grid.bounds, abs=1e-6)
    assert (from_bag.ml() == from_carmen.ml()).mean() > 0.99

    wrong = run_cli("map", str(bag.path), "--topic", "/odom", "--out", str(tmp_path / "wrong"))
    assert wrong.returncode == 2
    assert f"{bag.path}: topic /odom" in wrong.stderr and "Traceback" not in wrong.stderr
