"""tools/scan_order.py: a run's scans integrated in three orders give one
map, but for rounding."""

from __future__ import annotations

from typing import Any

import pytest

import covmap
from repo_tools import load_tool


@pytest.fixture(scope="module")
def tool() -> Any:
    return load_tool("scan_order")


def test_a_runs_scans_in_three_orders_give_one_map(tool: Any) -> None:
    building = covmap.Building.generate(0, area_m2=120)
    exploration, maps = tool.maps_in_orders(building, 150.0)
    assert exploration.scans > 300 and list(maps) == ["forwards", "backwards", "shuffled"]
    orders = tool.compare(exploration, maps, building.world.coverage(exploration.grid))
    assert [o.name for o in orders] == list(maps)
    assert orders[0].largest_difference == 0.0
    for o in orders:
        assert o.largest_difference < 1e-4 and o.moved_percent == 0.0 and o.blocked_differs == 0
        assert o.error == pytest.approx(orders[0].error, abs=1e-5)
        assert 0.0 < o.uncertain_percent < 100.0
