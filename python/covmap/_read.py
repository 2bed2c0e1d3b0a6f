"""Small files read on the Python side (sweep specs, learned models),
checked as the native readers check theirs: a regular file of at most
:data:`MAX_SMALL_FILE_BYTES`, so that a FIFO does not hang the reader and
``/dev/zero`` does not fill the memory; JSON and TOML nested at most
:data:`MAX_NESTING_DEPTH` deep (:func:`too_deep`, checked before the text
is parsed)."""

from __future__ import annotations

import os
import re
import stat
from typing import TYPE_CHECKING, Literal

import numpy as np

if TYPE_CHECKING:
    from pathlib import Path

__all__ = ["MAX_NESTING_DEPTH", "MAX_SMALL_FILE_BYTES", "read_small_file", "too_deep"]

MAX_NESTING_DEPTH = 64
"""The deepest a JSON or TOML file read here may nest its arrays and
tables/objects: far more than a sweep file (4) or a model file (2) needs,
and far less than where Python's parsers would hit the recursion limit."""

#: What in a JSON text may hold a bracket that nests nothing: its strings.
_JSON_QUOTED = re.compile(rb'"(?:[^"\\]|\\.)*"', re.DOTALL)
#: The same in TOML: its four kinds of strings, and its comments.
_TOML_QUOTED = re.compile(
    rb'"""(?:[^\\]|\\.)*?"""|\'\'\'.*?\'\'\'|"(?:[^"\\\n]|\\.)*"|\'[^\'\n]*\'|#[^\n]*',
    re.DOTALL,
)


def too_deep(data: bytes, syntax: Literal["json", "toml"]) -> str | None:
    """Why ``data`` (a JSON or TOML text) nests too deeply to be parsed, or
    ``None``: its arrays and objects (tables) nest more than
    :data:`MAX_NESTING_DEPTH` deep, counted by their brackets outside
    strings and comments, in time proportional to its size."""
    quoted = _JSON_QUOTED if syntax == "json" else _TOML_QUOTED
    bare = np.frombuffer(quoted.sub(b"", data), dtype=np.uint8)
    steps = np.isin(bare, (ord("["), ord("{"))).astype(np.int64) - np.isin(bare, (ord("]"), ord("}")))
    depth = int(np.cumsum(steps).max(initial=0))
    if depth > MAX_NESTING_DEPTH:
        return f"nested too deeply: {depth} levels of arrays and tables, more than the {MAX_NESTING_DEPTH} covmap reads"
    return None

MAX_SMALL_FILE_BYTES = 64 << 20
"""The largest sweep or model file read, bytes (64 MiB: far more than
any holds)."""


def read_small_file(path: str | Path) -> bytes:
    """The bytes of the regular file at ``path``; :class:`~covmap.FileIOError`
    naming the file for one that cannot be read, is no regular file (a
    directory, a FIFO, a device) or is larger than
    :data:`MAX_SMALL_FILE_BYTES`."""
    from covmap._errors import FileIOError

    def refuse(reason: str) -> FileIOError:
        error = FileIOError(f"{path}: {reason}")
        error.filename, error.strerror = str(path), reason
        return error

    try:
        info = os.stat(path)
    except OSError as e:
        raise FileIOError(e.errno, e.strerror, str(path)) from None
    if not stat.S_ISREG(info.st_mode):
        raise refuse("not a regular file")
    if info.st_size > MAX_SMALL_FILE_BYTES:
        raise refuse(f"{info.st_size} bytes is larger than the limit of {MAX_SMALL_FILE_BYTES} bytes")
    try:
        with open(path, "rb") as f:
            data = f.read(MAX_SMALL_FILE_BYTES + 1)
    except OSError as e:
        raise FileIOError(e.errno, e.strerror, str(path)) from None
    if len(data) > MAX_SMALL_FILE_BYTES:
        raise refuse(f"the file grew past the limit of {MAX_SMALL_FILE_BYTES} bytes while it was read")
    return data
