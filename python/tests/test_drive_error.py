"""python/tools/drive_error.py: a recorded drive's mean-map error split by
class of judged cell, the shares adding up to the mean error."""

from __future__ import annotations

import sys
from typing import Any

import numpy as np
import pytest
from repo_tools import PYTHON_TOOLS, load_tool


@pytest.fixture(scope="module")
def tool() -> Any:
    return load_tool("drive_error", PYTHON_TOOLS)


def test_the_classes_partition_the_judged_cells_and_the_shares_add_up(tool: Any) -> None:
    truth = np.array([[0.0, 0.0, 0.0, 0.0, 0.4, 1.0]])
    values = np.array([[0.9, 0.5, 0.1, 0.0, 0.7, 0.2]])
    judged = np.array([[True, True, True, True, True, False]])
    masks = tool.classes(values, truth, judged)
    assert list(masks) == list(tool.CLASSES)
    stacked = np.stack(list(masks.values())).astype(int)
    assert (stacked.sum(axis=0) == judged.astype(int)).all(), "each judged cell in exactly one class"
    assert [int(m.sum()) for m in masks.values()] == [1, 1, 2, 1]
    shares = tool.shares(values, truth, judged)
    total = sum(share for _, share in shares.values())
    assert total == pytest.approx(np.abs(values - truth)[judged].mean())
    assert shares["free, held covered"] == (1, pytest.approx(0.9 / 5))


def test_a_short_drive_is_reported(tool: Any, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setattr(sys, "argv", ["drive_error.py", "--scans", "10"])
    tool.main()
    out = capsys.readouterr().out
    assert out.startswith("corridor drive, ") and "office drive, " in out
    rows = [line for line in out.splitlines() if line.startswith("| coverage map") or line.startswith("| occupancy")]
    assert len(rows) == 6
    for row in rows:
        cells = row.split(" | ")
        shares = [float(c.split(", ")[1]) for c in cells[2:6]]
        assert float(cells[1]) == pytest.approx(sum(shares), abs=2e-4)
