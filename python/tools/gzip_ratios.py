"""How many times gzip logs inflate: the real CARMEN logs of the shared
data folder, and a log of one repeated comment line, against the bound a
gzip log is read to (``MAX_GZIP_RATIO`` of the core's
``log/readers/source.rs``). Prints one line a file; asserts nothing.

    python python/tools/gzip_ratios.py [--data ../shared/data]
"""

from __future__ import annotations

import argparse
import gzip
import zlib
from pathlib import Path

MAX_GZIP_RATIO = 100
"""The core's bound (``covmap_core::MAX_GZIP_RATIO``), for the comparison."""


def ratio(compressed: bytes) -> float:
    """Inflated bytes over compressed bytes of a gzip stream."""
    return len(gzip.decompress(compressed)) / len(compressed)


def main() -> None:
    default = Path(__file__).resolve().parents[3] / "shared" / "data"
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", type=Path, default=default, help="the shared data folder")
    args = parser.parse_args()
    logs = sorted((args.data / "carmen").glob("*.log.gz"))
    if not logs:
        print(f"no CARMEN logs under {args.data / 'carmen'}")
    for log in logs:
        print(f"{log.name}: inflates {ratio(log.read_bytes()):.1f} times")
    line = b"#" * 1000 + b"\n"
    z = zlib.compressobj(9, zlib.DEFLATED, 31)
    bomb = b"".join(z.compress(line) for _ in range(20_000)) + z.flush()
    print(f"20 MB of one comment line: inflates {ratio(bomb):.0f} times (bound: {MAX_GZIP_RATIO})")


if __name__ == "__main__":
    main()
