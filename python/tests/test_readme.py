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


class _PasteCheck:
    """An interactive prompt that compiles what is pasted into it, line by
    line as the prompt reads it, and runs nothing."""

    def __init__(self) -> None:
        import code

        errors: list[str] = []

        class Console(code.InteractiveConsole):
            def runcode(self, code: object) -> None:
                pass

            def showsyntaxerror(self, filename: str | None = None, **kwargs: object) -> None:
                import sys

                errors.append(str(sys.exc_info()[1]))

        self.console, self.errors = Console(), errors


def test_every_readme_python_block_pastes_into_a_prompt_as_written() -> None:
    readme = Path(__file__).resolve().parents[2] / "README.md"
    if not readme.is_file():
        pytest.skip("no README.md beside the package")
    blocks = re.findall(r"```python\n(.*?)```", readme.read_text(), flags=re.S)
    assert len(blocks) >= 3
    for block in blocks:
        check = _PasteCheck()
        more = False
        for line in block.splitlines():
            more = check.console.push(line)
        assert not more or check.console.push("") is False
        assert check.errors == [], (block, check.errors)


def test_the_paste_check_finds_a_loop_without_its_blank_line() -> None:
    check = _PasteCheck()
    for line in ["for i in range(2):", "    i", "i"]:
        check.console.push(line)
    assert check.errors
