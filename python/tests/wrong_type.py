"""What the tests of bad input share: which errors besides covmap's own a
call may raise. A call whose arguments do not bind to its signature, or an
argument of the wrong class (an object, a string, a path, a flag), raises
Python's own ``TypeError``, as numpy's and polars' calls do; every bad
value, numbers of the wrong kind included, raises a ``covmap.CovmapError``."""

from __future__ import annotations

import re

#: The note pyo3 adds to the error of an argument it could not convert.
ARGUMENT_NOTE = re.compile(r"while processing '(\w+)'")


def converted_argument(error: BaseException) -> str | None:
    """The argument whose conversion raised ``error``, if it is the
    ``TypeError`` of pyo3's conversion (which notes the argument), else
    ``None``."""
    if type(error) is not TypeError:
        return None
    for note in getattr(error, "__notes__", ()):
        match = ARGUMENT_NOTE.fullmatch(note)
        if match is not None:
            return match.group(1)
    return None
