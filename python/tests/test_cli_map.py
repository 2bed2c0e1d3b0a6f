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


SONAR_8RING = (
    "--bearings=-90,-37.5,-22.5,-7.5,7.5,22.5,37.5,90",
    "--length-unit", "0.001", "--angle-unit", "0.1deg", "--min-range", "0.17", "--max-range", "5",
    "--no-echo", "5110",
)  # fmt: skip
"""The sonar-8ring data set described as ``covmap map --help`` shows it."""


def test_the_sonar_ring_maps_as_its_options_describe_it(tmp_path: Path, shared_data: Callable[[str], Path]) -> None:
    poses, meas = shared_data("sonar-8ring/poses.txt"), shared_data("sonar-8ring/measurement.txt")
    args = ("map", str(poses), "--measurements", str(meas), "--resolution", "0.1")
    result = run_cli(*args, *SONAR_8RING, "--out", str(tmp_path / "a"))
    assert result.returncode == 0, result.stdout + result.stderr
    assert "413 of 8 beams, max range 5 m, sonar model" in result.stdout
    # Progress off a terminal: plain lines that count the 413 scans, once a map.
    assert "\r" not in result.stderr and "\x1b" not in result.stderr
    assert "scans into the coverage map 413/413" in result.stderr
    assert "scans into the occupancy grid 413/413" in result.stderr
    # The bearings from a file, the heading's unit as radians: the same map.
    bearings = tmp_path / "bearings.txt"
    bearings.write_text("-90 -37.5 -22.5 -7.5\n7.5 22.5 37.5 90\n")
    described = [a if not a.startswith("--bearings") else f"--bearings={bearings}" for a in SONAR_8RING]
    described[described.index("0.1deg")] = repr(math.pi / 1800)
    again = run_cli(*args, *described, "--out", str(tmp_path / "b"))
    assert again.returncode == 0, again.stdout + again.stderr
    first = covmap.CoverageMap.load(tmp_path / "a" / "coverage.npz")
    second = covmap.CoverageMap.load(tmp_path / "b" / "coverage.npz")
    np.testing.assert_array_equal(first.histograms, second.histograms)
    help_text = run_cli("map", "--help").stdout
    assert "--no-echo" in help_text and "--bearings" in help_text and "0.1deg" in help_text


@pytest.mark.parametrize(
    ("drop", "says"),
    [("--bearings", "bearings_deg"), ("--max-range", "max_range_m")],
)
def test_a_sonar_text_log_without_its_description_is_refused(
    tmp_path: Path, shared_data: Callable[[str], Path], drop: str, says: str
) -> None:
    poses, meas = shared_data("sonar-8ring/poses.txt"), shared_data("sonar-8ring/measurement.txt")
    options = [a for a in SONAR_8RING if not a.startswith(drop)]
    if drop == "--max-range":
        options.remove("5")
    result = run_cli("map", str(poses), "--measurements", str(meas), *options, "--out", str(tmp_path))
    assert result.returncode == 2
    assert says in result.stderr and drop in result.stderr and "Traceback" not in result.stderr
    assert not (tmp_path / "coverage.npz").exists()


@pytest.mark.parametrize(
    "option",
    ["--bearings=x,1", "--bearings=/no/such/file", "--angle-unit=grad", "--angle-unit=0",
     "--length-unit=-1", "--min-range=nan", "--no-echo=inf"],
)  # fmt: skip
def test_a_bad_sonar_description_is_a_usage_error(tmp_path: Path, option: str) -> None:
    result = run_cli("map", "p.txt", "--measurements", "m.txt", option, "--out", str(tmp_path))
    assert result.returncode == 2 and "Traceback" not in result.stderr
    assert option.split("=")[0] in result.stderr


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
