"""The bad-input corpus (``corpus.py``), run in subprocesses with a time
and an address-space limit: a case that panics, aborts, hangs or allocates
without bound fails here instead of taking pytest down.

Most cases share a process (in batches, for speed); those that may take
the interpreter down run in one each. Every case must succeed or raise a
``covmap.CovmapError`` (the written ones a given class, also a given
builtin, with a given text in the message), or, where the case allows it,
Python's own ``TypeError`` of a call that does not bind or of an argument
of the wrong class; a call that raised must leave the maps as they were.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

import pytest

sys.path.insert(0, str(Path(__file__).parent))

from corpus import Case, cases  # noqa: E402

RUNNER = Path(__file__).parent / "runner.py"
#: The address-space limit of a case's process: enough for covmap, numpy
#: and the small maps of the namespace, far from what an unbounded
#: allocation asks.
LIMIT_BYTES = 2 << 30
#: Cases a shared process runs.
BATCH = 500
#: Seconds a batch may take, and a case alone.
BATCH_TIMEOUT_S = 150.0
ALONE_TIMEOUT_S = 30.0

CASES = cases()


def _batches() -> list[list[Case]]:
    shared = [c for c in CASES if not c.alone]
    batches = [shared[i : i + BATCH] for i in range(0, len(shared), BATCH)]
    return batches + [[c] for c in CASES if c.alone]


BATCHES = _batches()
BATCH_OF = {c.id: i for i, batch in enumerate(BATCHES) for c in batch}
_RESULTS: dict[int, dict[str, dict[str, Any]]] = {}


def _run(index: int) -> dict[str, dict[str, Any]]:
    """The outcome of every case of batch ``index``, by id; a case during
    which the process died or timed out gets ``{"died": reason}``, the
    cases after it ``{"died": "not run ..."}``."""
    if index in _RESULTS:
        return _RESULTS[index]
    batch = BATCHES[index]
    alone = len(batch) == 1 and batch[0].alone
    with tempfile.TemporaryDirectory() as cwd:
        spec = Path(cwd) / "cases.json"
        spec.write_text(json.dumps([{"id": c.id, "code": c.code} for c in batch]))
        env = dict(os.environ, RAYON_NUM_THREADS="2")
        try:
            done = subprocess.run(
                [sys.executable, str(RUNNER), str(spec), str(LIMIT_BYTES)],
                cwd=cwd,
                env=env,
                capture_output=True,
                text=True,
                timeout=ALONE_TIMEOUT_S if alone else BATCH_TIMEOUT_S,
            )
            err = done.stderr
            shown = err if len(err) <= 3000 else f"{err[:2000]}\n...\n{err[-1000:]}"
            stdout, ending = done.stdout, f"exit status {done.returncode}: {shown}"
        except subprocess.TimeoutExpired as e:
            out = e.stdout or b""
            stdout = out.decode() if isinstance(out, bytes) else out
            ending = f"timed out after {e.timeout} s"
    results: dict[str, dict[str, Any]] = {}
    started = None
    for line in stdout.splitlines():
        record = json.loads(line)
        if "start" in record:
            started = record["start"]
        else:
            results[record["id"]] = record
            started = None
    for c in batch:
        if c.id not in results:
            reason = ending if c.id == started else f"not run: the process ended in {started!r} ({ending})"
            results[c.id] = {"id": c.id, "died": reason}
    _RESULTS[index] = results
    return results


def _need(package: str) -> None:
    """Skip a case without ``package`` (a failure under ``CI=true``: CI
    installs the extras)."""
    import importlib.util

    if importlib.util.find_spec(package) is None:
        if os.environ.get("CI") == "true":
            pytest.fail(f"{package} is not installed (CI=true: CI installs covmap's extras)")
        pytest.skip(f"{package} is not installed: pip install 'covmap[{package}]' to run this case")


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_bad_input(case: Case) -> None:
    if case.needs is not None:
        _need(case.needs)
    result = _run(BATCH_OF[case.id])[case.id]
    assert "died" not in result, f"{case.code}\n{result['died']}"
    if not result["raised"]:
        assert case.expect == "either", f"{case.code}\nreturned; expected {case.expect}"
        return
    if not result["covmap"]:
        python_type_error = result["type"] == "TypeError" and (
            case.allows == "binding" or (case.allows is not None and result["argument"] == case.allows)
        )
        assert python_type_error, f"{case.code}\nraised {result['type']}: {result['message']}\n{result.get('traceback')}"
    assert not result["changed"], f"{case.code}\nraised {result['type']} but changed a map"
    if case.expect != "either":
        assert case.expect in result["bases"], f"{case.code}\nraised {result['type']}: {result['message']}"
    if case.builtin is not None:
        assert case.builtin in result["bases"], f"{case.code}\n{result['type']} is no {case.builtin}"
    if case.mentions is not None:
        assert case.mentions in result["message"], f"{case.code}\nmessage: {result['message']}"
