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


def test_the_kinds_of_unsettled_histograms(tool: Any) -> None:
    split = np.full(16, 0.05 / 14, dtype=np.float32)
    split[3:5] = 0.475
    conflict = np.full(16, 0.2 / 14, dtype=np.float32)
    conflict[0], conflict[15] = 0.4, 0.4
    broad = np.full(16, 1 / 16, dtype=np.float32)
    is_split, is_conflict = tool.kinds(np.stack([split, conflict, broad]))
    assert is_split.tolist() == [True, False, False]
    assert is_conflict.tolist() == [False, True, False]


def test_a_short_run_splits_its_whole_uncertain_share(tool: Any) -> None:
    # 20 m leaves most rooms of a small building unentered and uncertain.
    building = covmap.Building.generate(0, area_m2=120)
    s = tool.split(building, 20.0)
    assert s.building == building.name and "limit" in s.run
    assert s.rooms_never_entered >= 1 and s.never_entered > 0.0 and s.elsewhere > 0.0
    assert s.never_entered + s.elsewhere == pytest.approx(s.uncertain, abs=1e-9)
    assert 0.0 <= s.split + s.conflict <= s.elsewhere + 1e-9
