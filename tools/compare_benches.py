"""Criterion benchmarks of two revisions, side by side in one run.

    python tools/compare_benches.py OLD_REV NEW_REV [--benches integrate,gain,planning]
        [--filter REGEX] [--measurement-time 5] [--rounds 2]

Each revision's benches are built in a worktree of it (``cargo bench
--no-run``, in the worktree's own target directory): an existing worktree
whose HEAD is that commit, else a new one under ``target/compare/``. Then each bench binary
runs with criterion's ``--bench`` flags, old and new alternately, ``--rounds``
times, so that the machine's load falls on both alike; a benchmark's figure
is the best of its rounds' medians. Prints a Markdown table: each benchmark's
median time at both revisions and the ratio new / old (below 1: faster).
The processor changes between sessions; the ratio is the figure.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
UNITS = {"ps": 1e-12, "ns": 1e-9, "µs": 1e-6, "us": 1e-6, "ms": 1e-3, "s": 1.0}
# criterion's line: "name    time:   [1.2345 ms 1.2400 ms 1.2456 ms]" (the name
# may stand on the line before when it is long).
TIME = re.compile(r"^(?P<name>\S.*?)?\s*time:\s+\[\S+ \S+ (?P<mid>\S+) (?P<unit>\S+) \S+ \S+\]")


def worktree(rev: str) -> Path:
    """A worktree whose HEAD is ``rev``: an existing one, or one made under
    target/compare/."""
    commit = subprocess.run(["git", "rev-parse", rev], cwd=ROOT, check=True, stdout=subprocess.PIPE, text=True).stdout.strip()
    listing = subprocess.run(["git", "worktree", "list", "--porcelain"], cwd=ROOT, check=True, stdout=subprocess.PIPE, text=True).stdout
    for block in listing.split("\n\n"):
        fields = dict(line.split(" ", 1) for line in block.splitlines() if " " in line)
        if fields.get("HEAD") == commit and Path(fields["worktree"]).is_dir():
            return Path(fields["worktree"])
    path = ROOT / "target" / "compare" / rev
    if not path.exists():
        subprocess.run(["git", "worktree", "add", "-q", "--detach", str(path), rev], cwd=ROOT, check=True)
    return path


def build(tree: Path, bench: str) -> Path:
    """Build ``bench`` in ``tree``, in its own target directory; the path of
    its binary."""
    env = {k: v for k, v in os.environ.items() if k != "CARGO_TARGET_DIR"}
    out = subprocess.run(
        ["cargo", "bench", "--no-run", "--bench", bench, "--message-format", "json"],
        cwd=tree,
        env=env,
        check=True,
        stdout=subprocess.PIPE,
        text=True,
    ).stdout
    for line in out.splitlines():
        message = json.loads(line)
        if message.get("reason") == "compiler-artifact" and message.get("target", {}).get("name") == bench:
            if message.get("executable"):
                return Path(message["executable"])
    raise SystemExit(f"no executable for bench {bench} in {tree}")


def run(binary: Path, tree: Path, args: argparse.Namespace) -> dict[str, float]:
    """Run a bench binary; each benchmark's median, seconds."""
    command = [str(binary), "--bench", "--warm-up-time", "1", "--measurement-time", str(args.measurement_time)]
    if args.filter:
        command.append(args.filter)
    out = subprocess.run(command, cwd=tree, check=True, stdout=subprocess.PIPE, text=True).stdout
    times: dict[str, float] = {}
    name = None
    for line in out.splitlines():
        m = TIME.match(line)
        if m:
            name = (m.group("name") or name or "?").strip()
            times[name] = float(m.group("mid")) * UNITS[m.group("unit")]
            name = None
        elif line.strip() and not line.startswith((" ", "Benchmarking", "Found", "Gnuplot", "change", "Warning")):
            name = line.strip()
    return times


def shown(seconds: float) -> str:
    for unit, scale in (("s", 1.0), ("ms", 1e-3), ("µs", 1e-6), ("ns", 1e-9)):
        if seconds >= scale:
            return f"{seconds / scale:.3g} {unit}"
    return f"{seconds:.3g} s"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("--benches", default="integrate,gain,planning")
    parser.add_argument("--filter", default="", help="criterion's filter (a regular expression)")
    parser.add_argument("--measurement-time", type=float, default=5.0)
    parser.add_argument("--rounds", type=int, default=2)
    args = parser.parse_args()
    revs = {rev: worktree(rev) for rev in (args.old, args.new)}
    print("| bench | benchmark | " + " | ".join(revs) + " | new / old |")
    print("| --- | --- | " + " | ".join("---:" for _ in revs) + " | ---: |")
    for bench in args.benches.split(","):
        binaries = {rev: build(tree, bench) for rev, tree in revs.items()}
        best: dict[str, dict[str, float]] = {rev: {} for rev in revs}
        for _ in range(args.rounds):
            for rev, tree in revs.items():
                print(f"running {bench} at {rev}", file=sys.stderr)
                for name, t in run(binaries[rev], tree, args).items():
                    best[rev][name] = min(t, best[rev].get(name, t))
        old, new = (best[rev] for rev in revs)
        for name in old:
            if name in new:
                print(f"| {bench} | `{name}` | {shown(old[name])} | {shown(new[name])} | {new[name] / old[name]:.3f} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
