"""Small files read on the Python side (sweep specs, learned models),
checked as the native readers check theirs: a regular file of at most
:data:`MAX_SMALL_FILE_BYTES`, so that a FIFO does not hang the reader and
``/dev/zero`` does not fill the memory."""

from __future__ import annotations

import os
import stat
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from pathlib import Path

__all__ = ["MAX_SMALL_FILE_BYTES", "read_small_file"]

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
