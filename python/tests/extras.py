"""The optional extras' packages for the tests that need them: a skip with
a message where one is missing, a failure under ``CI=true`` (CI installs
every extra)."""

from __future__ import annotations

import importlib
import os
from typing import Any

import pytest


def need_extra(module: str, extra: str, tests: str) -> Any:
    """``module`` imported, or a skip naming ``covmap[extra]`` (a failure
    under ``CI=true``); ``tests`` says which tests need it."""
    try:
        return importlib.import_module(module)
    except ImportError:
        if os.environ.get("CI") == "true":
            pytest.fail(f"{module} is not installed (CI=true: CI installs covmap[{extra}])")
        # At a module's top, where the tests that need it import it.
        pytest.skip(f"{module} is not installed: pip install 'covmap[{extra}]' to run {tests}", allow_module_level=True)
