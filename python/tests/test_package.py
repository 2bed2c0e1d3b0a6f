from __future__ import annotations

import doctest

import covmap
import covmap._native


def test_public_api_is_exported() -> None:
    for name in covmap.__all__:
        assert hasattr(covmap, name), name
    assert set(covmap._native.__all__) <= set(covmap.__all__)


def test_version_matches_the_distribution() -> None:
    from importlib.metadata import version

    assert covmap.__version__ == version("covmap")


def test_docstring_examples() -> None:
    failures, tests = doctest.testmod(covmap)
    assert tests > 0 and failures == 0
