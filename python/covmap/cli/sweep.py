"""``covmap sweep``: the runs of a sweep file, on the local cores or on Dask."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from covmap.cli import _options

if TYPE_CHECKING:
    import argparse

NAME = "sweep"
"""The command's name: ``covmap sweep``."""

HELP = "run the explorations of a sweep file (JSON or TOML) and write their figures as CSV"
"""The command's line in ``covmap --help``."""

DESCRIPTION = (
    "Read SPECS (a .json or .toml file: runs, a list of specs, each a table of covmap.explore "
    "arguments with world a built-in name and strategy a name or a table such as "
    "{ name = \"counting\", n = 50 }; defaults, keys every run takes unless it gives them; seeds, a list in place of seed, "
    "for one spec a seed), check every spec, run them all on this machine's cores (one run a core) or on "
    "the Dask scheduler at --dask, with a progress bar, and write one CSV row per spec to "
    "--out, atomically. Runs that fail are listed in the CSV and on standard error, and the "
    "command exits 1; a bad spec is named by its index before anything runs (exit 2)."
)
"""What ``covmap sweep --help`` says the command does."""


def add_arguments(command: argparse.ArgumentParser) -> None:
    """The command's arguments."""
    command.add_argument("specs", type=Path, metavar="SPECS", help="the sweep file, .json or .toml")
    command.add_argument(
        "--out", type=Path, required=True, metavar="FILE", help="the CSV file to write, one row per spec"
    )
    _options.add_dask(command, local=False)


def outputs(args: argparse.Namespace) -> list[Path]:
    """The file the command writes."""
    return [args.out]


def run(args: argparse.Namespace) -> int:
    """Run the sweep, write its CSV."""
    from covmap._errors import SweepError
    from covmap._sweep import sweep
    from covmap._sweep_files import read_specs, write_csv

    specs = read_specs(args.specs)
    with _options.executor(args) as executor:
        try:
            summaries = sweep(specs, executor=executor)
        except SweepError as e:
            print(f"wrote {write_csv(args.out, e.results, e.failures)}")
            raise
    print(f"{len(summaries)} runs, {sum(s.seconds for s in summaries):.1f} s of runs")
    print(f"wrote {write_csv(args.out, summaries)}")
    return 0
