from __future__ import annotations

from typing import Any

import numpy as np
import pytest

import covmap


def test_prior(grid: covmap.Grid) -> None:
    occupancy = covmap.OccupancyGrid(grid)
    assert occupancy.grid == grid
    for array in (occupancy.probabilities(), occupancy.log_odds(), occupancy.counts()):
        assert array.shape == (40, 60) and array.dtype == np.float32
    np.testing.assert_array_equal(occupancy.probabilities(), 0.5)
    np.testing.assert_array_equal(occupancy.log_odds(), 0.0)
    np.testing.assert_array_equal(occupancy.counts(), 0.0)
    assert repr(occupancy).startswith("OccupancyGrid(Grid(")


def test_a_repeatedly_hit_cell_becomes_occupied(grid: covmap.Grid, model: Any) -> None:
    occupancy = covmap.OccupancyGrid(grid)
    pose = (0.5, 1.025, 0.0)
    for _ in range(20):
        # Ends at x = 1.51, inside the cell [1.50, 1.55) of column 30.
        returned = occupancy.integrate(pose, np.array([1.01]), np.array([0.0]), model)  # type: ignore[func-returns-value]
        assert returned is None
    row, col = grid.world_to_cell(1.51, 1.025) or (-1, -1)
    assert (row, col) == (20, 30)
    p = occupancy.probabilities()
    assert p[row, col] > 0.9, "the end point's cell"
    assert p[row, col - 5] < 0.1, "a cell the beam passed"
    assert p[row + 5, col] == 0.5, "a cell no beam reached"
    assert occupancy.counts()[row, col] == 20
    assert occupancy.counts()[row, col + 3] == 0, "cells behind are not counted"
    assert np.abs(occupancy.log_odds()).max() <= 5.0 + 1e-6, "log-odds are clamped"
    np.testing.assert_allclose(
        occupancy.probabilities(), 1.0 / (1.0 + np.exp(-occupancy.log_odds())), rtol=1e-6
    )


def test_no_echo_clears_without_marking(grid: covmap.Grid) -> None:
    occupancy = covmap.OccupancyGrid(grid)
    sonar = covmap.SonarModel()
    occupancy.integrate((0.5, 1.025, 0.0), [sonar.max_range_m], [0.0], sonar)
    assert occupancy.probabilities().max() == pytest.approx(0.5)
    assert occupancy.probabilities().min() < 0.5
