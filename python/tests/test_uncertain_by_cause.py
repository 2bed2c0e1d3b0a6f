"""tools/uncertain_by_cause.py: a run's uncertain cells split between the
rooms never entered and the rest, the two adding up to the run's share."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

import covmap
from repo_tools import load_tool


@pytest.fixture(scope="module")
def tool() -> Any:
    return load_tool("uncertain_by_cause")


def test_inside_reads_a_floor_of_rectangles(tool: Any) -> None:
    floor = np.array([[0.0, 0.0, 1.0, 1.0], [2.0, 0.0, 3.0, 1.0]])
    points = np.array([[0.5, 0.5], [1.5, 0.5], [2.5, 0.9], [2.5, 1.1]])
    assert tool.inside(points, floor).tolist() == [True, False, True, False]


def test_a_short_run_splits_its_whole_uncertain_share(tool: Any) -> None:
    # 20 m leaves most rooms of a small building unentered and uncertain.
    building = covmap.Building.generate(0, area_m2=120)
    name, missed, rest, rooms, run, total = tool.split(building, 20.0)
    assert name == building.name and "limit" in run
    assert rooms >= 1 and missed > 0.0 and rest > 0.0
    assert missed + rest == pytest.approx(total, abs=1e-9)
