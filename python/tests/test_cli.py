"""The command line as a user runs it."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import numpy as np
import pytest

import covmap
from covmap.experiments import fig1
from covmap.cli import parser
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


def assert_clean_error(
    result: subprocess.CompletedProcess[str], command: str, option: str, message: str
) -> None:
    """An argparse error about ``option`` of ``command``, exit status 2, no traceback."""
    assert result.returncode == 2, result.stdout + result.stderr
    assert "Traceback" not in result.stderr
    error = result.stderr.splitlines()[-1]
    assert error.startswith(f"covmap {command}: error: argument {option}: expected "), error
    assert message in error, error


@pytest.mark.parametrize(
    ("args", "option", "message"),
    [
        (["fig1", "--seed", "-1"], "--seed", "expected a seed from 0 to 2**64 - 1, got -1"),
        (["fig1", "--seed", "abc"], "--seed", "expected an integer, got abc"),
        (["fig3", "--seed", str(2**64)], "--seed", f"expected a seed from 0 to 2**64 - 1, got {2**64}"),
        (["gain", "--seed", str(2**64)], "--seed", "expected a seed from 0 to 2**64 - 1"),
        (["gain", "--seed", "1.5"], "--seed", "expected an integer, got 1.5"),
        (["fig1", "--readings", "abc"], "--readings", "expected an integer, got abc"),
        (["fig1", "--readings", "0"], "--readings", "expected an integer from 1 to 1000000, got 0"),
        (["gain", "--scans", str(10**20)], "--scans", "expected an integer from 1 to 1000000"),
        (["world", "corridor", "--resolution", "1e300"], "--resolution", "to 1000, got 1e300"),
        (["world", "corridor", "--resolution", "1e-7"], "--resolution", "from 1e-06 to 1000, got 1e-7"),
        (["world", "corridor", "--resolution", "nan"], "--resolution", "expected a length in metres"),
        (["world", "corridor", "--resolution=-inf"], "--resolution", "expected a length in metres"),
        (["world", "x.map", "--wall-thickness", "1e300"], "--wall-thickness", "at most 100, got 1e300"),
        (["world", "x.map", "--wall-thickness", "500"], "--wall-thickness", "at most 100, got 500"),
        (["world", "x.pgm", "--image-resolution", "1e10"], "--image-resolution", "to 1000, got 1e10"),
        (["world", "x.pgm", "--image-resolution", "0"], "--image-resolution", "expected a length in metres"),
    ],
)
def test_bad_option_values_are_clean_errors(args: list[str], option: str, message: str) -> None:
    # Rejected by the parser before anything runs: no traceback, no internal names.
    result = run_cli(*args)
    assert_clean_error(result, args[0], option, message)
    assert "invalid _" not in result.stderr


@pytest.mark.parametrize("command", ["fig1", "fig3", "gain"])
def test_seeds_range_over_unsigned_64_bit_integers(command: str) -> None:
    for seed in (0, 2**64 - 1):
        assert parser().parse_args([command, "--seed", str(seed)]).seed == seed


def test_the_largest_seed_runs(tmp_path: Path) -> None:
    result = run_cli("fig1", "--out", str(tmp_path), "--seed", str(2**64 - 1), "--readings", "20")
    assert result.returncode in (0, 1), result.stderr
    assert f"seed {2**64 - 1}" in result.stdout
    assert (tmp_path / "fig1.png").is_file()


def test_the_largest_resolution_runs(tmp_path: Path) -> None:
    result = run_cli("world", "corridor", "--out", str(tmp_path), "--resolution", "1000")
    assert result.returncode == 0, result.stderr
    assert "coverage grid: 1 x 1 cells of 1000 m" in result.stdout


def test_help_texts() -> None:
    fig1_help = run_cli("fig1", "--help").stdout
    assert "80 % of one cell" in fig1_help and "%%" not in fig1_help
    for command in ("fig1", "world", "fig3", "gain"):
        result = run_cli(command, *(["x"] if command == "world" else []), "--help")
        assert result.returncode == 0, result.stderr
        assert f"(default covmap-out/{command})" in " ".join(result.stdout.split())
        assert parser().parse_args([command, *(["x"] if command == "world" else [])]).out == Path(
            "covmap-out", command
        )
    world_help = " ".join(run_cli("world", "--help").stdout.split())
    assert ".yaml/.yml" in world_help


def test_readme_command_table_lists_every_option() -> None:
    readme = Path(__file__).resolve().parents[2] / "README.md"
    if not readme.is_file():
        pytest.skip("no README.md beside the package")
    rows = {
        line.split("`")[1].split()[1]: line.split("`")[1]
        for line in readme.read_text().splitlines()
        if line.startswith("| `covmap ")
    }
    assert sorted(rows) == [
        "benchmark",
        "explore",
        "fig1",
        "fig2",
        "fig3",
        "fig7",
        "gain",
        "learn",
        "map",
        "sweep",
        "table1",
        "view",
        "world",
    ]
    for command, row in rows.items():
        usage = run_cli(command, "--help").stdout.split("\n\n")[0]
        options = set(re.findall(r"\[(--[a-z-]+)", usage)) - {"--help"}
        assert options, usage
        for option in options:
            assert f"[{option} " in row or f"[{option}]" in row, (command, option)  # an option, or a flag


def test_save_figure_takes_the_longest_file_name(tmp_path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from covmap.plot import save_figure

    fig, ax = plt.subplots()
    try:
        ax.plot([0, 1], [0, 1])
        name = "a" * 251 + ".png"  # 255 bytes: NAME_MAX on Linux
        path = save_figure(fig, tmp_path / name)
    finally:
        plt.close(fig)
    assert path == tmp_path / name
    assert path.read_bytes()[:8] == PNG_SIGNATURE
    assert [p.name for p in tmp_path.iterdir()] == [name], "no temporary file left"


def test_save_figure_leaves_nothing_behind_when_writing_fails(tmp_path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from covmap.plot import save_figure

    fig, _ = plt.subplots()

    def fail(*args: object, **kwargs: object) -> None:
        raise OSError("disk full")

    fig.savefig = fail  # type: ignore[method-assign]
    try:
        with pytest.raises(OSError, match="disk full"):
            save_figure(fig, tmp_path / "a.png")
    finally:
        plt.close(fig)
    assert list(tmp_path.iterdir()) == []
