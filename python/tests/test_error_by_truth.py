"""python/tools/error_by_truth.py: a run's map error split by what the
truth holds, and free cells held covered by their distance from an
obstacle."""

from __future__ import annotations

import sys
from typing import Any

import numpy as np
import pytest
from repo_tools import PYTHON_TOOLS, load_tool


@pytest.fixture(scope="module")
def tool() -> Any:
    return load_tool("error_by_truth", PYTHON_TOOLS)


def test_distances_are_four_connected_and_capped(tool: Any) -> None:
    mask = np.zeros((5, 7), dtype=bool)
    mask[2, 1] = True
    d = tool.distance_from(mask, 4)
    assert d[2, 1] == 0 and d[2, 2] == 1 and d[3, 2] == 2 and d[2, 4] == 3
    assert d[0, 6] == 4 and d.max() == 4


def test_a_short_run_is_reported_by_truth(tool: Any, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    for extra in ([], ["--clear-no-echo"]):
        monkeypatch.setattr(sys, "argv", ["error_by_truth.py", "generated:1:60", "--max-path-m", "5", *extra])
        tool.main()
        out = capsys.readouterr().out
        assert out.startswith("generated:1:60: ") and "contacts" in out
        assert [line.split()[0] for line in out.splitlines()[2:5]] == ["free", "partly", "fully"]
