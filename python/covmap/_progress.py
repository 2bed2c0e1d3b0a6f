"""Progress while a command runs.

On a terminal: a tqdm bar when tqdm is installed, else a line on standard
error that rewrites itself. On anything else (a log file, a pipe, a CI
job's output): plain lines, with neither carriage returns nor escape codes,
a few per task: one at each tenth of a known total, or at 1, 2, 5, 10, 20,
50, ... items of an unknown one, and one at the end."""

from __future__ import annotations

import importlib
import sys
from typing import Any, TextIO


def _is_terminal(stream: TextIO) -> bool:
    isatty = getattr(stream, "isatty", None)
    try:
        return bool(isatty()) if callable(isatty) else False
    except (OSError, ValueError):
        return False


def _milestone(count: int) -> bool:
    """Whether ``count`` is 1, 2 or 5 times a power of ten."""
    while count >= 10 and count % 10 == 0:
        count //= 10
    return count in (1, 2, 5)


class Progress:
    """A progress display of ``total`` items (``None``: unknown), counting
    ``unit``\\ s. :meth:`update` advances it and shows ``status``; use it as
    a context manager, which ends the line (or closes the bar, or writes
    the last plain line)."""

    def __init__(self, total: int | None, unit: str, *, stream: TextIO | None = None) -> None:
        self.stream = stream if stream is not None else sys.stderr
        self.total, self.unit, self.count = total, unit, 0
        self.terminal = _is_terminal(self.stream)
        self.bar: Any = None
        self.status = ""
        self.written = -1
        if not self.terminal:
            return
        try:
            tqdm = importlib.import_module("tqdm").tqdm
        except ImportError:
            return
        self.bar = tqdm(total=total, unit=f" {unit}", file=self.stream, dynamic_ncols=True)

    def _line(self) -> str:
        of = f"/{self.total}" if self.total is not None else ""
        return f"{self.unit} {self.count}{of}" + (f": {self.status}" if self.status else "")

    def _due(self) -> bool:
        if self.total is None or self.total <= 0:
            return _milestone(self.count)
        tenth = (10 * self.count) // self.total
        return tenth != (10 * (self.count - 1)) // self.total or self.count == 1

    def update(self, status: str = "") -> None:
        """One more item done; ``status`` says where the work stands."""
        self.count += 1
        self.status = status
        if self.bar is not None:
            if status:
                self.bar.set_postfix_str(status, refresh=False)
            self.bar.update(1)
        elif self.terminal:
            self.stream.write(f"\r{self._line()}\x1b[K")
            self.stream.flush()
        elif self._due():
            self.stream.write(self._line() + "\n")
            self.stream.flush()
            self.written = self.count

    def __enter__(self) -> Progress:
        return self

    def __exit__(self, *exc: object) -> None:
        if self.bar is not None:
            self.bar.close()
        elif self.terminal:
            if self.count:
                self.stream.write("\n")
                self.stream.flush()
        elif self.count and self.written != self.count:
            self.stream.write(self._line() + "\n")
            self.stream.flush()
