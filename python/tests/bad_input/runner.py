"""Runs a batch of the bad-input corpus in this process, under an
address-space limit: ``python runner.py CASES.json LIMIT_BYTES``, in a
working directory the caller made (the cases' files go inside it).

Prints one JSON line per case: ``{"start": id}`` before it runs (so that a
process that dies is known to have died in it), then its outcome: whether
it raised, the exception's class, the names of its bases, its message, the
argument pyo3 noted on it (``wrong_type.converted_argument``), and whether
a map of the namespace changed although the call raised.
"""

from __future__ import annotations

import json
import os
import resource
import sys
import tempfile
import traceback
from typing import Any

sys.path.insert(0, __file__.rsplit("/", 1)[0])
sys.path.insert(0, __file__.rsplit("/", 2)[0])

from corpus import SETUP  # noqa: E402
from wrong_type import converted_argument  # noqa: E402


def snapshot(namespace: dict[str, Any]) -> tuple[bytes, ...]:
    """The state of the namespace's maps, to tell whether an error changed them."""
    m, o = namespace["m"], namespace["o"]
    return (m.histograms.tobytes(), o.log_odds().tobytes(), o.counts().tobytes())


def main() -> None:
    cases = json.loads(open(sys.argv[1]).read())
    limit = int(sys.argv[2])
    # Inside the working directory the test made (and removes), so that no
    # directory outlives the run, even one of a process that died.
    namespace: dict[str, Any] = {"tmp": tempfile.mkdtemp(prefix="covmap-bad-input-", dir=os.getcwd())}
    exec(SETUP, namespace)
    # After the setup: the limit is for the cases.
    resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    covmap = namespace["covmap"]
    out = sys.stdout
    for case in cases:
        print(json.dumps({"start": case["id"]}), file=out, flush=True)
        before = snapshot(namespace)
        result: dict[str, Any] = {"id": case["id"], "raised": False}
        try:
            exec(case["code"], dict(namespace))
        except BaseException as e:  # noqa: BLE001 (every outcome is reported)
            result.update(
                raised=True,
                type=type(e).__name__,
                bases=[c.__name__ for c in type(e).__mro__],
                covmap=isinstance(e, covmap.CovmapError),
                message=str(e)[:500],
                argument=converted_argument(e),
                changed=snapshot(namespace) != before,
            )
            if not isinstance(e, covmap.CovmapError):
                result["traceback"] = traceback.format_exc()[-1500:]
        print(json.dumps(result), file=out, flush=True)


if __name__ == "__main__":
    main()
