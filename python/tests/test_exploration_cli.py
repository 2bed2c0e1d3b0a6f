"""``covmap explore`` and ``covmap table1``, their experiments and figures,
and unknown cells drawn as unknown."""

from __future__ import annotations

import csv
import io
from pathlib import Path

import numpy as np
import pytest

import covmap
from cli_helpers import PNG_SIGNATURE, run_cli
from covmap.experiments import exploration, table1
from test_exploration import room


def rendered(ax: object) -> np.ndarray:
    """The RGB pixels of the figure of ``ax``, rows from the top."""
    fig = ax.figure  # type: ignore[attr-defined]
    fig.canvas.draw()
    return np.asarray(fig.canvas.buffer_rgba())[:, :, :3].copy()


def pixel_at(ax: object, x: float, y: float) -> tuple[int, int, int]:
    """The colour drawn at the world point ``(x, y)``."""
    fig = ax.figure  # type: ignore[attr-defined]
    pixels = rendered(ax)
    px, py = ax.transData.transform((x, y))  # type: ignore[attr-defined]
    height = pixels.shape[0]
    r, g, b = pixels[int(round(height - py)), int(round(px))]
    del fig
    return int(r), int(g), int(b)


def test_unobserved_cells_are_drawn_unknown_not_white() -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import to_rgb

    grid = covmap.Grid(origin=(0.0, 0.0), resolution=0.1, shape=(20, 20))
    cmap = covmap.CoverageMap(grid)
    cmap.integrate((0.5, 1.05, 0.0), np.array([1.0]), np.array([0.0]), covmap.LaserModel())
    observed = cmap.observed()
    assert observed[10, 10] and not observed[3, 15]
    unknown = tuple(round(255 * c) for c in to_rgb(covmap.plot.UNKNOWN_COLOR))
    ml = cmap.ml()
    assert ml[3, 15] == ml[10, 10] == 0.0  # an unseen cell reads free on the ML map
    for draw in (
        lambda ax: covmap.plot.plot_map(ml, grid, ax, observed=observed),
        lambda ax: covmap.plot.plot_map(np.ma.masked_where(~observed, ml), grid, ax),
    ):
        fig, ax = plt.subplots(figsize=(4, 4), dpi=100)
        try:
            draw(ax)
            seen_free = pixel_at(ax, 1.05, 1.05)  # cell (10, 10): the beam passed
            unseen = pixel_at(ax, 1.55, 0.35)  # cell (3, 15): nothing reached it
        finally:
            plt.close(fig)
        assert seen_free == (255, 255, 255)
        assert unseen != (255, 255, 255)
        assert np.abs(np.subtract(unseen, unknown)).max() <= 2
    with pytest.raises(covmap.ArrayShapeError, match="observed must be a bool array"):
        covmap.plot.plot_map(ml, grid, observed=observed.astype(np.uint8))


def test_a_watched_run_keeps_few_frames_spread_to_its_end() -> None:
    calls: list[int] = []
    run = exploration.run(
        room(),
        covmap.Strategy.counting(1),
        world_name="room",
        frames=4,
        progress=lambda e, step: calls.append(step.index),
        seed=2,
        resolution=0.1,
    )
    r = run.result
    assert r.termination in {"certain", "stagnated", "no_goal"}
    assert calls == list(range(r.steps)) and r.steps > 8
    steps = [f.step for f in run.frames]
    assert len(steps) == 4 and steps[0] == 0 and steps[-1] == r.steps
    assert steps == sorted(set(steps))
    first, last = run.frames[0].ml_coverage, run.frames[-1].ml_coverage
    assert first.mask.all()  # nothing observed before the first scan
    np.testing.assert_array_equal(last.mask, ~r.map.observed())
    np.testing.assert_allclose(last.filled(0.0), np.where(r.map.observed(), r.map.ml(), 0.0), atol=0.5 / 250)
    np.testing.assert_array_equal(run.frames[-1].trajectory, r.trajectory)
    text = exploration.summary(run)
    assert "counting" in text and f"{r.path_length_m:.2f} m" in text and "faster than real time" in text
    with pytest.raises(covmap.InvalidParameterError, match="`frames` = 1"):
        exploration.run(room(), covmap.Strategy.frontier(), frames=1)


def test_table1_rows_their_statistics_and_csv() -> None:
    methods = table1.METHODS[1:2] + table1.METHODS[3:]
    seen: list[tuple[str, int]] = []
    t = table1.run(
        room(),
        world_name="room",
        seeds=[0, 1],
        methods=methods,
        progress=lambda m, seed, r: seen.append((m.label, seed)),
        resolution=0.1,
    )
    assert seen == [(m.label, s) for m in methods for s in (0, 1)]
    assert [row.method for row in t.rows] == list(methods) and len(t.runs) == 4
    row = t.rows[0]
    paths = [r.path_length_m for r in row.runs]
    mean, spread = row.stat("path_length_m")
    assert mean == pytest.approx(np.mean(paths)) and spread == pytest.approx(np.std(paths, ddof=1))
    assert table1.mean_and_spread([2.0]) == (2.0, 0.0)
    text = table1.table(t)
    assert "counting n = 1" in text and "26.6 m / 21 %" in text and "nearest frontier" in text
    assert "resolution=0.1" in text
    rows = list(csv.DictReader(io.StringIO(table1.csv_text(t))))
    assert len(rows) == 4 and list(rows[0]) == list(table1.CSV_FIELDS)
    assert [float(r["path_length_m"]) for r in rows[:2]] == paths
    assert rows[0]["strategy"] == "Strategy.counting(n=1, discount_beyond_m=None)"


def test_table1_methods_are_the_papers() -> None:
    labels = {m.label: m for m in table1.METHODS}
    assert labels["coverage maps, alpha 0.5"].strategy == covmap.Strategy.coverage(0.5)
    assert labels["counting n = 50, discounted"].strategy == covmap.Strategy.counting(
        50, covmap.DEFAULT_DISCOUNT_BEYOND_M
    )
    assert [(m.paper_path_m, m.paper_uncertain) for m in table1.METHODS] == [
        (89.1, 0.0),
        (26.6, 0.21),
        (90.6, 0.015),
        (None, None),
    ]


def test_explore_command_writes_its_pictures(tmp_path: Path) -> None:
    result = run_cli("explore", "--max-steps", "4", "--frames", "3", "--seed", "1", "--out", str(tmp_path))
    # A run that ends at a limit exits 1 (the built-in worlds end by rule).
    assert result.returncode == 1, result.stderr
    assert "termination                       limit" in result.stdout
    assert "at a limit" in result.stdout
    assert "step 4" in result.stderr or "4 step" in result.stderr  # the progress line or bar
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == [
        "corridor-coverage-entropy.png",
        "corridor-coverage-map.png",
        "corridor-coverage-trajectory.csv",
        "corridor-coverage.gif",
        "corridor-coverage.npz",
        "corridor-coverage.pgm",
        "corridor-coverage.yaml",
    ]
    for name in names[:2]:
        assert (tmp_path / name).read_bytes()[:8] == PNG_SIGNATURE
    assert "frame" in result.stderr  # drawing the animation shows its progress
    from PIL import Image

    with Image.open(tmp_path / "corridor-coverage.gif") as gif:
        assert gif.format == "GIF" and 2 <= getattr(gif, "n_frames") <= 3


def test_explore_command_other_strategies_and_the_laser(tmp_path: Path) -> None:
    result = run_cli(
        "explore",
        "--strategy",
        "counting",
        "--n",
        "3",
        "--discount-beyond-m",
        "2",
        "--sensor",
        "laser",
        "--max-steps",
        "2",
        "--frames",
        "2",
        "--out",
        str(tmp_path),
    )
    assert result.returncode == 1, result.stderr
    assert "Strategy.counting(n=3, discount_beyond_m=2.0)" in result.stdout
    assert (tmp_path / "corridor-counting.gif").is_file()


def test_table1_command_writes_csv_and_chart(tmp_path: Path) -> None:
    result = run_cli("table1", "--seeds", "1", "--max-steps", "2", "--out", str(tmp_path))
    assert result.returncode == 0, result.stderr
    for figures in ("89.1 m / 0 %", "26.6 m / 21 %", "90.6 m / 1.5 %"):
        assert figures in result.stdout
    assert "options: max_steps=2" in result.stdout
    rows = list(csv.DictReader(io.StringIO((tmp_path / "table1.csv").read_text())))
    assert [r["method"] for r in rows] == [m.label for m in table1.METHODS]
    assert all(r["termination"] == "limit" and r["steps"] == "2" for r in rows)
    assert (tmp_path / "table1.png").read_bytes()[:8] == PNG_SIGNATURE
    assert sorted(p.name for p in tmp_path.iterdir()) == ["table1.csv", "table1.png"]


@pytest.mark.parametrize(
    ("args", "option", "message"),
    [
        (["explore", "--alpha", "1.5"], "--alpha", "expected a weight in [0, 1]"),
        (["explore", "--n", "0"], "--n", "expected an integer from 1 to 1000000"),
        (["explore", "--frames", "1"], "--frames", "expected an integer from 2 to 1000"),
        (["explore", "--max-path-m", "-1"], "--max-path-m", "expected a distance in metres"),
        (["explore", "--max-steps", "0"], "--max-steps", "expected an integer from 1 to 1000000"),
        (["explore", "--strategy", "greedy"], "--strategy", "invalid choice"),
        (["explore", "--discount-beyond-m", "0"], "--discount-beyond-m", "expected a distance in metres"),
        (["table1", "--seeds", "0"], "--seeds", "expected an integer from 1 to 1000000"),
    ],
)
def test_bad_options_are_clean_errors(args: list[str], option: str, message: str) -> None:
    result = run_cli(*args)
    assert result.returncode == 2
    assert option in result.stderr and message in result.stderr
    assert "Traceback" not in result.stderr


def test_an_unknown_world_is_a_clean_error(tmp_path: Path) -> None:
    for command in ("explore", "table1"):
        result = run_cli(command, "--world", "atlantis", "--out", str(tmp_path))
        assert result.returncode == 2 and "atlantis" in result.stderr and "corridor" in result.stderr
        assert "Traceback" not in result.stderr
    assert not any(tmp_path.iterdir())


def test_a_large_plan_is_drawn_thinned_to_the_pixels(tmp_path: Path) -> None:
    """A grid of more cells than the figures have pixels is thinned before
    it is drawn: the figures and the animation are written, the animation
    as wide as its figure, its frames showing the run."""
    building = covmap.Building.generate(5, area_m2=550)
    run = exploration.run(building.world, covmap.Strategy.frontier(), frames=3, max_steps=3, seed=0)
    assert max(run.result.grid.shape) > 480  # more cells than the GIF's 480-pixel width
    paths = covmap.plot.plot_exploration(run, tmp_path)
    assert [p.name for p in paths] == ["world-frontier-map.png", "world-frontier-entropy.png", "world-frontier.gif"]
    from PIL import Image

    with Image.open(paths[2]) as gif:
        assert getattr(gif, "n_frames") == len(run.frames) and gif.size[0] == 6 * 80
        first = np.asarray(gif.convert("RGB")).copy()
        gif.seek(gif.n_frames - 1)
        last = np.asarray(gif.convert("RGB")).copy()
    assert not np.array_equal(first, last)  # the path and the map grew
