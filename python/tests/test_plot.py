"""covmap.plot draws into matplotlib axes; figures are saved atomically."""

from __future__ import annotations

import doctest
from collections.abc import Iterator
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import covmap  # noqa: E402
from covmap.plot import plot_map, plot_trajectory, plot_world, save_figure  # noqa: E402
from cli_helpers import PNG_SIGNATURE  # noqa: E402


@pytest.fixture(autouse=True)
def close_figures() -> Iterator[None]:
    yield
    plt.close("all")


def test_plot_map_puts_rows_along_y() -> None:
    grid = covmap.Grid(origin=(1.0, -2.0), resolution=0.5, shape=(4, 6))
    values = np.zeros(grid.shape)
    values[3, 0] = 1.0  # top-left cell: x in [1, 1.5), y in [-0.5, 0)
    ax = plot_map(values, grid, title="t")
    image = ax.images[0]
    assert image.get_extent() == [1.0, 4.0, -2.0, 0.0]
    assert image.origin == "lower"
    assert ax.get_title() == "t"
    with pytest.raises(covmap.ArrayShapeError):
        plot_map(np.zeros((6, 4)), grid)


def test_plot_world_draws_every_polygon(tmp_path: Path) -> None:
    world = covmap.World.builtin("corridor")
    ax = plot_world(world)
    assert len(ax.patches) == len(world)
    x0, y0, x1, y1 = world.bounds
    (lx0, lx1), (ly0, ly1) = ax.get_xlim(), ax.get_ylim()
    assert lx0 <= x0 and lx1 >= x1 and ly0 <= y0 and ly1 >= y1
    glass = [p.get_facecolor() for p, m in zip(ax.patches, world.materials) if m == "glass"]
    assert glass and all(c == matplotlib.colors.to_rgba("lightskyblue") for c in glass)
    # A polygon with a hole is one patch of two closed rings (5 + 5 vertices).
    path = tmp_path / "holed.geojson"
    path.write_text(
        '{"type": "Polygon", "coordinates": [[[0,0],[4,0],[4,4],[0,4],[0,0]],'
        "[[1,1],[1,3],[3,3],[3,1],[1,1]]]}"
    )
    holed = covmap.World.from_file(path)
    assert len(holed.holes[0]) == 1
    _, ax2 = plt.subplots()
    plot_world(holed, ax2)
    assert len(ax2.patches) == 1
    assert np.asarray(ax2.patches[0].get_path().vertices).shape == (10, 2)


def test_plot_trajectory_accepts_points_and_poses() -> None:
    ax = plot_trajectory(np.array([[0.0, 0.0], [1.0, 1.0], [2.0, 1.0]]))
    np.testing.assert_array_equal(ax.lines[0].get_xdata(), [0.0, 1.0, 2.0])
    ax = plot_trajectory([(0.0, 0.0, 0.0), (1.0, 0.0, 1.5)], headings=True)
    assert len(ax.collections) == 1  # the heading arrows
    with pytest.raises(covmap.ArrayShapeError):
        plot_trajectory(np.zeros((3, 4)))


def test_save_figure_is_atomic_and_repeatable(tmp_path: Path) -> None:
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    a = save_figure(fig, tmp_path / "sub" / "a.png")
    b = save_figure(fig, tmp_path / "sub" / "b.png")
    assert a.read_bytes()[:8] == PNG_SIGNATURE
    assert a.read_bytes() == b.read_bytes()
    assert sorted(p.name for p in (tmp_path / "sub").iterdir()) == ["a.png", "b.png"]


def test_docstring_examples() -> None:
    failures, tests = doctest.testmod(covmap.plot)
    assert tests > 0 and failures == 0
