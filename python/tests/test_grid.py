from __future__ import annotations

import copy
import math
import pickle

import pytest

import covmap


def test_attributes(grid: covmap.Grid) -> None:
    assert grid.origin == (0.0, 0.0)
    assert grid.resolution == 0.05
    assert grid.shape == (40, 60)
    assert (grid.rows, grid.cols) == (40, 60)
    assert grid.bounds == pytest.approx((0.0, 0.0, 3.0, 2.0))


def test_rows_run_along_y_and_columns_along_x(grid: covmap.Grid) -> None:
    assert grid.world_to_cell(0.12, 0.37) == (7, 2)
    x, y = grid.cell_center(7, 2)
    assert (x, y) == pytest.approx((0.125, 0.375))


def test_world_to_cell_round_trips_and_excludes_the_upper_edges() -> None:
    g = covmap.Grid(origin=(-2.0, 1.0), resolution=0.25, shape=(8, 12))
    for row in range(g.rows):
        for col in range(g.cols):
            assert g.world_to_cell(*g.cell_center(row, col)) == (row, col)
    assert g.world_to_cell(-2.0001, 1.5) is None
    assert g.world_to_cell(1.0, 1.5) is None
    assert g.world_to_cell(0.999, 2.999) == (7, 11)
    assert g.contains(-2.0, 1.0) and not g.contains(1.0, 1.0)


@pytest.mark.parametrize(
    "kwargs",
    [
        {"origin": (0.0, 0.0), "resolution": 0.0, "shape": (3, 3)},
        {"origin": (0.0, 0.0), "resolution": -0.05, "shape": (3, 3)},
        {"origin": (0.0, 0.0), "resolution": math.nan, "shape": (3, 3)},
        {"origin": (math.nan, 0.0), "resolution": 0.05, "shape": (3, 3)},
        {"origin": (0.0, 0.0), "resolution": 0.05, "shape": (0, 3)},
        {"origin": (0.0, 0.0), "resolution": 0.05, "shape": (-1, 3)},
        {"origin": (0.0, 0.0), "resolution": 0.05, "shape": (2**40, 2**40)},
    ],
)
def test_invalid_geometry_raises(kwargs: dict[str, object]) -> None:
    with pytest.raises(covmap.InvalidGridError) as info:
        covmap.Grid(**kwargs)  # type: ignore[arg-type]
    assert isinstance(info.value, ValueError)
    assert isinstance(info.value, covmap.CovmapError)


def test_arguments_are_keyword_only() -> None:
    with pytest.raises(TypeError):
        covmap.Grid((0.0, 0.0), 0.05, (3, 3))  # type: ignore[call-arg]


def test_equality_hash_repr_and_pickle(grid: covmap.Grid) -> None:
    same = covmap.Grid(origin=(0.0, 0.0), resolution=0.05, shape=(40, 60))
    other = covmap.Grid(origin=(0.0, 0.0), resolution=0.05, shape=(40, 61))
    assert grid == same and hash(grid) == hash(same)
    assert grid != other
    assert grid != "a grid"
    assert eval(repr(grid), {"Grid": covmap.Grid}) == grid
    assert pickle.loads(pickle.dumps(grid)) == grid
    assert copy.deepcopy(grid) == grid
    assert len({grid, same, other}) == 2


def test_covering_rounds_up_to_whole_cells() -> None:
    g = covmap.Grid.covering((0.0, 0.0, 1.01, 0.5), resolution=0.1)
    assert g.shape == (5, 11)
    with pytest.raises(covmap.InvalidGridError):
        covmap.Grid.covering((1.0, 0.0, 0.0, 1.0), resolution=0.1)
