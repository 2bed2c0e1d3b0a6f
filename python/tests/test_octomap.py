"""The Intel map against an OctoMap of the same beams (tools/compare_octomap.py):
on the cells both know they agree, occupied or not, on at least 95 %. Needs
pyoctomap (``pip install pyoctomap``); skipped with a message without it."""

from __future__ import annotations

from pathlib import Path
from typing import Callable

import pytest

import covmap
from repo_tools import load_tool


def test_the_intel_map_agrees_with_octomap(shared_data: Callable[[str], Path]) -> None:
    pytest.importorskip("pyoctomap", reason="pyoctomap is not installed (pip install pyoctomap)")
    tool = load_tool("compare_octomap")
    log = covmap.Log.from_carmen(shared_data("carmen/intel-corrected.log.gz"))[:150]
    model = covmap.LaserModel()
    grid = tool.aligned_grid(log, 0.05, 10.0)
    cmap = covmap.CoverageMap(grid)
    cmap.integrate_log(log, model)
    tree, _ = tool.octomap_of(log, 0.05, model.max_range_m)
    share, both = tool.agreement(cmap, tree, 0.05)
    assert both > 50_000
    assert share >= 0.95, share
