"""What the command-line tests share: running ``python -m covmap`` and the PNG signature."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def run_cli(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    """Run the ``covmap`` command in a fresh interpreter, as a user would."""
    return subprocess.run(
        [sys.executable, "-m", "covmap", *args],
        capture_output=True,
        text=True,
        timeout=300,
        cwd=cwd,
        check=False,
    )
