"""The ``covmap`` command line (also ``python -m covmap``).

One module a command (``fig1``, ``fig2``, ``world``, ``fig3``, ``learn``,
``gain``, ``explore``, ``table1``, ``fig7``, ``benchmark``, ``sweep``, ``map``), each with its
``NAME``, ``HELP`` and ``DESCRIPTION``, ``add_arguments(parser)``,
``outputs(args)`` (the files it writes, checked before it runs: see
:func:`covmap.cli._options.check_outputs`) and ``run(args) -> exit status``;
:func:`parser` gives each its subcommand.
"""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING

from covmap._errors import CovmapError
from covmap._native import __version__
from covmap.cli import _options, benchmark, explore, fig1, fig2, fig3, fig7, gain, learn, map, sweep, table1, view, world

if TYPE_CHECKING:
    from collections.abc import Sequence

COMMANDS = (fig1, fig2, world, fig3, learn, gain, explore, table1, fig7, benchmark, sweep, map, view)
"""The command modules, in the order ``covmap --help`` lists them."""


def parser() -> argparse.ArgumentParser:
    """The argument parser, one subcommand per experiment."""
    p = argparse.ArgumentParser(
        prog="covmap", description="Coverage maps (Stachniss and Burgard, 2003)."
    )
    p.add_argument("--version", action="version", version=f"covmap {__version__}")
    commands = p.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for module in COMMANDS:
        command = commands.add_parser(module.NAME, help=module.HELP, description=module.DESCRIPTION)
        module.add_arguments(command)
        command.set_defaults(func=module.run, outputs=module.outputs)
    return p


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    args = parser().parse_args(argv)
    try:
        _options.check_outputs(args.outputs(args))
        status: int = args.func(args)
    except (CovmapError, OSError) as e:
        # Bad names, bad files: say what is wrong, without a traceback.
        print(f"covmap {args.command}: error: {e}", file=sys.stderr)
        return 2 if isinstance(e, ValueError) else 1
    return status
