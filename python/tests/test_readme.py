"""The README's Python example runs as written."""

from __future__ import annotations

import re
from pathlib import Path

import pytest


def test_readme_python_example_runs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    readme = Path(__file__).resolve().parents[2] / "README.md"
    if not readme.is_file():
        pytest.skip("no README.md beside the package")
    blocks = re.findall(r"```python\n(.*?)```", readme.read_text(), flags=re.S)
    assert blocks, "README.md has no Python example"
    monkeypatch.chdir(tmp_path)
    namespace: dict[str, object] = {}
    exec(compile(blocks[0], str(readme), "exec"), namespace)
    plan = namespace["plan"]
    assert plan.path.ndim == 2 and plan.path.shape[1] == 2  # type: ignore[attr-defined]
    assert namespace["gains"].shape == (1,)  # type: ignore[attr-defined]
