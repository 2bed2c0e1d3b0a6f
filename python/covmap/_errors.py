"""The exceptions of covmap.

Every error covmap raises for bad input is a :class:`CovmapError`; those caused
by a bad value are also a :class:`ValueError` (a cell index out of range is an
:class:`IndexError`, an array of the wrong dtype a :class:`TypeError`, a file
that cannot be read an :class:`OSError`, an integer beyond 64 bits an
:class:`OverflowError`, a result that does not fit in memory a
:class:`MemoryError`), so code that catches the builtin keeps working. A robot that fails during an exploration run raises
:class:`RobotError`, a :class:`RuntimeError`; a sweep whose runs raised,
:class:`SweepError`, one too. The native module raises these classes.
"""

from __future__ import annotations

import re
from typing import Any

__all__ = [
    "ArrayDtypeError",
    "ArrayShapeError",
    "CellOutOfBoundsError",
    "CovmapError",
    "FileFormatError",
    "FileIOError",
    "InvalidBearingError",
    "InvalidGridError",
    "InvalidHistogramError",
    "InvalidHistoryError",
    "IntegerOverflowError",
    "InvalidParameterError",
    "InvalidPolygonError",
    "InvalidPoseError",
    "InvalidExecutorError",
    "InvalidRangeError",
    "InvalidSpecError",
    "InvalidActionError",
    "InvalidGoalError",
    "InvalidStartError",
    "InvalidTypeError",
    "InvalidValueError",
    "LengthMismatchError",
    "MainGuardError",
    "MapBusyError",
    "MissingDependencyError",
    "OutOfMemoryError",
    "PoseOutsideMapError",
    "RobotError",
    "SchedulerError",
    "SweepError",
    "UnknownWorldError",
]


class CovmapError(Exception):
    """Base class of every covmap error."""

    def add_note(self, note: str) -> None:
        """Add ``note`` to the exception; the note with which the native
        module names an argument it could not convert (``while processing
        'resolution'``) goes into the message instead, so that the message
        itself names the argument."""
        match = _ARGUMENT_NOTE.fullmatch(note)
        if match is not None and len(self.args) == 1 and isinstance(self.args[0], str):
            self.args = (f"argument '{match.group(1)}': {self.args[0]}",)
            return
        # BaseException.add_note is Python 3.11's; before, notes are dropped.
        add = getattr(super(), "add_note", None)
        if add is not None:
            add(note)


_ARGUMENT_NOTE = re.compile(r"while processing '(\w+)'")

#: The most characters of a value an error message quotes.
QUOTED_CHARS = 60


def quoted(value: object) -> str:
    """``value`` as an error message quotes it: its ``repr``, cut to
    :data:`QUOTED_CHARS` characters (a cut one says how long it was); an
    integer too large for Python to print by its bit length, any other
    value whose ``repr`` fails by its type."""
    try:
        text = repr(value)
    except Exception:  # noqa: BLE001 (an int beyond Python's digit limit, a broken __repr__)
        if isinstance(value, int):
            return f"an integer of {value.bit_length()} bits"
        return f"a {type(value).__name__} that cannot be shown"
    if len(text) > QUOTED_CHARS:
        return f"{text[:QUOTED_CHARS]}... ({len(text)} characters)"
    return text


class InvalidGridError(CovmapError, ValueError):
    """A grid was described with an unusable geometry."""


class InvalidParameterError(CovmapError, ValueError):
    """A sensor-model or map parameter (or a bin count) is out of its valid range."""


class IntegerOverflowError(InvalidParameterError, OverflowError):
    """A number argument lies beyond what a 64-bit number holds: an integer
    outside ``-2**63`` to ``2**63 - 1`` (outside its own range too: a seed
    goes up to ``2**64 - 1``), a float beyond float64's ``1.8e308``; the
    message names the argument, quotes the value and states the range the
    argument takes. An :class:`InvalidParameterError` (a
    :class:`ValueError`) and an :class:`OverflowError`, as Python's own
    conversions raise."""


class InvalidRangeError(CovmapError, ValueError):
    """A range reading is NaN, infinite or negative."""


class InvalidBearingError(CovmapError, ValueError):
    """A bearing is NaN or infinite, or so large that added to the heading it
    overflows."""


class InvalidPoseError(CovmapError, ValueError):
    """A pose has a non-finite component."""


class PoseOutsideMapError(CovmapError, ValueError):
    """A pose lies outside the map."""


class LengthMismatchError(CovmapError, ValueError):
    """Two inputs that must have the same length do not (ranges and bearings)."""


class CellOutOfBoundsError(CovmapError, IndexError):
    """A cell index lies outside the grid."""


class InvalidHistogramError(CovmapError, ValueError):
    """Histogram data handed in does not describe a valid map."""


class InvalidHistoryError(CovmapError, ValueError):
    """A stored entropy history holds an entropy no map can have (NaN, infinite,
    negative, or above the prior's ``ln(bins)``)."""




class OutOfMemoryError(CovmapError, MemoryError):
    """A map or a result needs more memory than can be had (a grid of many
    cells, a read-out of a large map); the message says what and how many
    bytes. Nothing was changed."""


class ArrayShapeError(CovmapError, ValueError):
    """An array argument has the wrong number of dimensions or the wrong shape."""


class ArrayDtypeError(CovmapError, TypeError):
    """An array argument has the wrong element type (covmap never converts silently)."""


class InvalidTypeError(CovmapError, TypeError):
    """An argument covmap converts itself has the wrong type: a number that
    is no number (a string, a bool where a count is asked), a model that is
    neither a SonarModel nor a LaserModel, a pickled state of the wrong
    form, arguments that exclude each other. (A call whose arguments do not
    bind to the signature, and an object argument of the wrong class, raise
    Python's own :class:`TypeError`, of which this is a subclass.)"""


class InvalidPolygonError(CovmapError, ValueError):
    """A polygon is not a usable obstacle (too few vertices, a non-finite
    coordinate, no area, edges that cross); the message names its index."""


class InvalidValueError(CovmapError, ValueError):
    """One element of an input array is unusable (a NaN ray origin, an infinite angle)."""


class UnknownWorldError(CovmapError, ValueError):
    """No built-in world has the requested name; the message lists those that do."""


class InvalidStartError(CovmapError, ValueError):
    """An exploration cannot start where asked (the robot's disc overlaps an
    obstacle), or the robot fits nowhere to start; the message gives the
    position and the reason."""


class InvalidGoalError(CovmapError, ValueError):
    """A goal given to an exploration run (``Exploration.step(goal=...)``,
    a custom strategy's answer) that the robot cannot go to: not finite,
    off the map, or not reachable on the map it has built; the message gives
    the goal and the reason. The run is as it was."""


class InvalidActionError(CovmapError, ValueError):
    """An action the exploration environment (:mod:`covmap.gym`) cannot
    take: out of the action space, masked (a lattice goal the robot cannot
    reach on its map), or given outside an episode. The episode is as it
    was."""


class RobotError(CovmapError, RuntimeError):
    """The robot failed during an exploration run: its sensor or its drive
    could not do what the loop asked. Not caused by a bad argument: a
    :class:`RuntimeError`, not a :class:`ValueError`."""


class FileFormatError(CovmapError, ValueError):
    """A world or log file is malformed or degenerate.

    ``filename`` names the file, ``place`` where in it (a line, a feature, a
    pixel) and ``reason`` what is wrong there; the message says all three.
    """

    filename: str | None = None
    place: str | None = None
    reason: str | None = None


class FileIOError(CovmapError, OSError):
    """A file could not be read or written (``errno``, ``strerror`` and
    ``filename`` as for any :class:`OSError`; ``errno`` is ``None`` where
    covmap refused the file itself, a directory given for a file, say)."""

    def __str__(self) -> str:
        # OSError's text, once ``filename`` is set, is built from ``errno`` and
        # ``strerror`` alone: without an errno it would read
        # "[Errno None] ...", so the message (which names the file and the
        # reason) is the text then.
        if self.errno is None and len(self.args) == 1:
            return str(self.args[0])
        return super().__str__()


class InvalidSpecError(CovmapError, ValueError):
    """A spec of :func:`covmap.sweep` cannot run (an unknown key, a value of
    the wrong type or out of range, a world that does not pickle). ``index``
    is the spec's position in the list, ``reason`` what is wrong with it;
    the message says both."""

    def __init__(self, index: int, reason: str) -> None:
        super().__init__(f"spec {index}: {reason}")
        self.index = index
        self.reason = reason

    def __reduce__(self) -> tuple[type[InvalidSpecError], tuple[int, str]]:
        return type(self), (self.index, self.reason)


class InvalidExecutorError(CovmapError, ValueError):
    """An executor handed to :func:`covmap.sweep` cannot run its runs (no
    ``submit``, or a process pool that forks: covmap's thread pool does not
    survive a fork, and the children would wait for it forever)."""


class MainGuardError(CovmapError, RuntimeError):
    """:func:`covmap.sweep` (or :func:`covmap.dask_client` with local
    workers) was called by a script's module-level code outside ``if
    __name__ == "__main__":``. Worker processes are spawned, and each
    imports the script again: it would start the call again in every
    worker. The message names the script, the line and the fix."""


class MapBusyError(CovmapError, RuntimeError):
    """A map was used from inside the progress callback of its own
    ``integrate_log`` (read, integrated into, saved...): the map is busy in
    that call until it returns. Nothing was changed."""


class SchedulerError(CovmapError, OSError):
    """A Dask scheduler could not be reached at the address given (nothing
    listens there, or it did not answer in time)."""


class MissingDependencyError(CovmapError, ImportError):
    """An optional dependency a feature needs is not installed; the message
    says what to install (``pip install covmap[dask]`` for Dask)."""


class SweepError(CovmapError, RuntimeError):
    """Some runs of a sweep raised. Raised by :func:`covmap.sweep` after
    every run has ended, so that no result is lost: ``results`` holds one
    entry per spec in the specs' order (a ``RunSummary``, or ``None`` where
    the run failed), ``failures`` a ``SweepFailure`` per failed run (its
    spec's index, the exception's type name and message, and the exception
    itself)."""

    def __init__(self, results: list[Any], failures: list[Any]) -> None:
        shown = "; ".join(f"spec {f.index}: {f.error_type}: {f.message}" for f in failures[:5])
        more = f"; and {len(failures) - 5} more" if len(failures) > 5 else ""
        super().__init__(f"{len(failures)} of {len(results)} runs failed: {shown}{more}")
        self.results = results
        self.failures = failures

    def __reduce__(self) -> tuple[type[SweepError], tuple[list[Any], list[Any]]]:
        return type(self), (self.results, self.failures)
