"""The world, fig3 and gain commands as a user runs them."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

import covmap
from covmap.experiments import planning_step
from cli_helpers import PNG_SIGNATURE, run_cli


def numbers(line: str) -> list[float]:
    return [float(x) for x in re.findall(r"-?\d+\.\d+", line)]


def line_starting(stdout: str, prefix: str) -> str:
    lines = [line for line in stdout.splitlines() if line.startswith(prefix)]
    assert len(lines) == 1, stdout
    return lines[0]


def assert_pngs(directory: Path, names: list[str]) -> None:
    assert sorted(p.name for p in directory.iterdir()) == sorted(names), "no temporary file left"
    for name in names:
        assert (directory / name).read_bytes()[:8] == PNG_SIGNATURE


def test_world_end_to_end(tmp_path: Path) -> None:
    result = run_cli("world", "corridor", "--out", str(tmp_path))
    assert result.returncode == 0, result.stderr
    assert_pngs(tmp_path, ["corridor-world.png", "corridor-coverage.png"])
    world = covmap.World.builtin("corridor")
    bounds = numbers(line_starting(result.stdout, "bounds:"))
    x0, y0, x1, y1 = world.bounds
    np.testing.assert_allclose(bounds[:4], [x0, x1, y0, y1], atol=5e-4)
    area = numbers(line_starting(result.stdout, "obstacle area:"))
    grid = covmap.Grid.covering(world.bounds, resolution=0.05)
    assert area[0] == pytest.approx(world.coverage(grid).sum() * 0.05**2, abs=5e-4)
    assert area[-1] == pytest.approx(world.polygon_area_m2, abs=5e-4)
    assert area[0] < area[-1], "overlapping walls count once in the union"


def test_world_from_a_file_and_resolution(tmp_path: Path) -> None:
    path = tmp_path / "square.geojson"
    path.write_text('{"type": "Polygon", "coordinates": [[[0.23,0.37],[1.23,0.37],[1.23,1.37],[0.23,1.37]]]}')
    result = run_cli("world", str(path), "--out", str(tmp_path / "out"), "--resolution", "0.1")
    assert result.returncode == 0, result.stderr
    assert numbers(line_starting(result.stdout, "obstacle area:"))[0] == pytest.approx(1.0, abs=1e-3)
    assert "0.1 m" in line_starting(result.stdout, "coverage grid:")
    assert_pngs(tmp_path / "out", ["square-world.png", "square-coverage.png"])


def test_world_errors_exit_non_zero(tmp_path: Path) -> None:
    unknown = run_cli("world", "atlantis", "--out", str(tmp_path))
    assert unknown.returncode == 2
    assert "no built-in world named" in unknown.stderr and "Traceback" not in unknown.stderr
    broken = tmp_path / "broken.geojson"
    broken.write_text("{")
    bad_file = run_cli("world", str(broken), "--out", str(tmp_path))
    assert bad_file.returncode == 2 and "broken.geojson" in bad_file.stderr
    missing = run_cli("world", str(tmp_path / "missing.map"), "--out", str(tmp_path))
    assert missing.returncode == 1 and "missing.map" in missing.stderr
    assert run_cli("world", "corridor", "--resolution", "0").returncode == 2


def test_gain_end_to_end(tmp_path: Path) -> None:
    result = run_cli("gain", "--out", str(tmp_path), "--seed", "2")
    assert result.returncode == 0, result.stderr
    assert_pngs(tmp_path, ["gain.png"])
    step = planning_step.run(covmap.World.builtin("corridor"), scans=3, seed=2, alpha=0.5)
    assert step.plan.pose is not None and step.plan.gain is not None and step.plan.cost is not None
    chosen = numbers(line_starting(result.stdout, "chosen viewpoint:"))
    np.testing.assert_allclose(chosen[:3], step.plan.pose, atol=5e-4)
    assert chosen[3] == pytest.approx(step.plan.gain, abs=5e-4)
    assert chosen[4] == pytest.approx(step.plan.cost, abs=5e-4)
    candidates = line_starting(result.stdout, "candidates:")
    assert candidates.startswith(f"candidates: {len(step.plan.candidates)} ")
    again = run_cli("gain", "--out", str(tmp_path / "again"), "--seed", "2")
    assert again.stdout.replace(str(tmp_path / "again"), str(tmp_path)) == result.stdout
    assert (tmp_path / "again" / "gain.png").read_bytes() == (tmp_path / "gain.png").read_bytes()


def test_gain_alpha_and_arguments(tmp_path: Path) -> None:
    nearest = run_cli("gain", "--out", str(tmp_path / "a0"), "--alpha", "0", "--scans", "2")
    greedy = run_cli("gain", "--out", str(tmp_path / "a1"), "--alpha", "1", "--scans", "2")
    assert nearest.returncode == greedy.returncode == 0, nearest.stderr + greedy.stderr
    near = numbers(line_starting(nearest.stdout, "chosen viewpoint:"))
    far = numbers(line_starting(greedy.stdout, "chosen viewpoint:"))
    assert near[4] <= far[4] and near[3] <= far[3]  # cost, gain
    assert run_cli("gain", "--alpha", "1.5").returncode == 2
    assert run_cli("gain", "--scans", "0").returncode == 2
    assert run_cli("gain", "--world", "atlantis", "--out", str(tmp_path)).returncode == 2


def test_fig3_end_to_end(tmp_path: Path) -> None:
    result = run_cli("fig3", "--out", str(tmp_path), "--seed", "1")
    assert result.returncode == 0, result.stderr
    assert_pngs(tmp_path, ["fig3-truth.png", "fig3-ml.png", "fig3-occupancy.png"])
    figures = covmap.run_fig3(1)
    assert f"{figures['cells_reached']} cells reached" in line_starting(result.stdout, "Fig. 3")
    ml = numbers(line_starting(result.stdout, "coverage map, ML"))
    occupancy = numbers(line_starting(result.stdout, "occupancy grid"))
    assert ml == pytest.approx([figures["mae_ml"]["all"], figures["mae_ml"]["partial"]], abs=5e-5)
    assert occupancy == pytest.approx(
        [figures["mae_occupancy"]["all"], figures["mae_occupancy"]["partial"]], abs=5e-5
    )
    assert ml[0] < occupancy[0]
    likelihood = numbers(line_starting(result.stdout, "log-likelihood"))
    assert likelihood[0] == pytest.approx(figures["log_likelihood"], abs=0.05)


def test_run_fig3_result() -> None:
    r = covmap.run_fig3(1)
    grid = r["grid"]
    assert isinstance(grid, covmap.Grid)
    for key, dtype in [("truth", np.float64), ("ml", np.float32), ("occupancy", np.float32), ("reached", np.bool_)]:
        assert r[key].shape == grid.shape and r[key].dtype == dtype, key
    assert r["cells_reached"] == int(r["reached"].sum())
    np.testing.assert_array_equal(r["truth"], covmap.World.builtin("corridor").coverage(grid))
    assert r["poses"].shape[1] == 3 and r["readings"] == 24 * len(r["poses"])
    assert r["mae_ml"]["all"] < r["mae_occupancy"]["all"]
    again = covmap.run_fig3(1)
    np.testing.assert_array_equal(r["ml"], again["ml"])
    assert not np.array_equal(r["poses"], covmap.run_fig3(2)["poses"])


@pytest.mark.parametrize("name", ["corridor", "office"])
def test_start_pose_is_free_near_the_west_end_of_the_passage(name: str) -> None:
    world = covmap.World.builtin(name)
    x, y, theta = planning_step.start_pose(world)
    assert not covmap.Robot().collides(world, (x, y))
    assert theta == 0.0
    x0, _, x1, _ = world.bounds
    assert x < x0 + 0.1 * (x1 - x0)
    if name == "corridor":
        assert abs(y - 1.3) <= 0.1  # the documented centre line
    else:
        assert 8.5 < y < 11.0  # the office's corridor
    # Looking east, the passage is long.
    assert world.cast((x, y), [0.0], 50.0)[0] > 0.8 * (x1 - x0)
