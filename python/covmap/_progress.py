"""Progress while a command runs: a tqdm bar when tqdm is installed, else a
line on standard error that rewrites itself."""

from __future__ import annotations

import importlib
import sys
from typing import Any, TextIO


class Progress:
    """A progress display of ``total`` items (``None``: unknown), counting
    ``unit``\\ s. :meth:`update` advances it and shows ``status``; use it as
    a context manager, which ends the line (or closes the bar)."""

    def __init__(self, total: int | None, unit: str, *, stream: TextIO | None = None) -> None:
        self.stream = stream if stream is not None else sys.stderr
        self.total, self.unit, self.count = total, unit, 0
        self.bar: Any = None
        try:
            tqdm = importlib.import_module("tqdm").tqdm
        except ImportError:
            return
        self.bar = tqdm(total=total, unit=f" {unit}", file=self.stream, dynamic_ncols=True)

    def update(self, status: str) -> None:
        """One more item done; ``status`` says where the work stands."""
        self.count += 1
        if self.bar is not None:
            self.bar.set_postfix_str(status, refresh=False)
            self.bar.update(1)
            return
        of = f"/{self.total}" if self.total is not None else ""
        self.stream.write(f"\r{self.unit} {self.count}{of}: {status}\x1b[K")
        self.stream.flush()

    def __enter__(self) -> Progress:
        return self

    def __exit__(self, *exc: object) -> None:
        if self.bar is not None:
            self.bar.close()
        elif self.count:
            self.stream.write("\n")
            self.stream.flush()
