"""The repository's scripts under ``tools/`` and ``python/tools/``, loaded
as modules for their tests (a skip where the tests run outside the
repository)."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from typing import Any

import pytest

TOOLS = Path(__file__).resolve().parents[2] / "tools"
PYTHON_TOOLS = Path(__file__).resolve().parents[1] / "tools"


def load_tool(name: str, under: Path = TOOLS) -> Any:
    """``NAME.py`` of the folder ``under`` (``tools/`` by default) as a
    module, or a skip if it is absent."""
    path = under / f"{name}.py"
    if not path.is_file():
        pytest.skip(f"{path} is absent (the test runs from the repository)")
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    # Registered first, as an import would: dataclasses look their module up.
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module
