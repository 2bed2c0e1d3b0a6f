"""The command line as a user runs it."""

from __future__ import annotations

from pathlib import Path

import numpy as np

import covmap
from covmap import fig1
from cli_helpers import PNG_SIGNATURE, run_cli


def table_lines(stdout: str) -> list[str]:
    return [line for line in stdout.splitlines() if not line.startswith("wrote ")]


def test_version() -> None:
    result = run_cli("--version")
    assert result.returncode == 0
    assert result.stdout.strip() == f"covmap {covmap.__version__}"


def test_fig1_end_to_end(tmp_path: Path) -> None:
    result = run_cli("fig1", "--out", str(tmp_path))
    assert result.returncode == 0, result.stdout + result.stderr
    png = tmp_path / "fig1.png"
    assert png.read_bytes()[:8] == PNG_SIGNATURE
    assert [p.name for p in tmp_path.iterdir()] == ["fig1.png"], "no temporary file left"
    lines = table_lines(result.stdout)
    rows = [line.split() for line in lines if line.strip()[:4] in ("0.20", "0.50", "0.80")]
    assert [r[0] for r in rows] == ["0.20", "0.50", "0.80"]
    for r in rows:
        fraction, ml, occupancy = float(r[0]), float(r[1]), float(r[3])
        assert abs(ml - fraction) <= 1 / 15 + 1e-3
        assert occupancy > 0.9
        assert r[4:] == ["yes", "yes"]
    assert lines[-1] == "PASS"


def test_fig1_default_out_dir(tmp_path: Path) -> None:
    result = run_cli("fig1", "--readings", "50", cwd=tmp_path)
    assert (tmp_path / "covmap-out" / "fig1" / "fig1.png").is_file(), result.stderr


def test_fig1_is_deterministic(tmp_path: Path) -> None:
    a = run_cli("fig1", "--out", str(tmp_path / "a"), "--seed", "3", "--readings", "100")
    b = run_cli("fig1", "--out", str(tmp_path / "b"), "--seed", "3", "--readings", "100")
    assert table_lines(a.stdout) == table_lines(b.stdout)
    assert (tmp_path / "a" / "fig1.png").read_bytes() == (tmp_path / "b" / "fig1.png").read_bytes()


def test_fig1_runs_depend_on_the_seed_only() -> None:
    first = fig1.run_all(seed=3, readings=50)
    again = fig1.run_all(seed=3, readings=50)
    other = fig1.run_all(seed=4, readings=50)
    for x, y in zip(first, again):
        np.testing.assert_array_equal(x.histogram, y.histogram)
    assert any(not np.array_equal(x.histogram, z.histogram) for x, z in zip(first, other))


def test_fig1_fails_loudly_when_the_outcome_does_not_hold(tmp_path: Path) -> None:
    # One reading cannot make the occupancy grid sure of anything (p = 0.7).
    result = run_cli("fig1", "--out", str(tmp_path), "--readings", "1")
    assert result.returncode == 1
    assert "FAIL" in result.stdout
    assert (tmp_path / "fig1.png").is_file(), "the figure is written either way"


def test_bad_arguments_exit_2(tmp_path: Path) -> None:
    assert run_cli("fig1", "--readings", "0").returncode == 2
    assert run_cli("no-such-command").returncode == 2
    assert run_cli().returncode == 2
