"""Command line: ``persson <command> ...`` (also ``python -m persson``).

Each command lives in its own module of :mod:`persson.commands` exposing ``NAME``, ``HELP``,
``add_arguments(parser)`` and ``run(args) -> int``; this module only dispatches. Every command prints where
its output went.
"""

from __future__ import annotations

import argparse
import importlib
import sys

__all__ = ["main", "COMMANDS"]

#: Command modules, in the order ``--help`` lists them.
COMMANDS = ("demo", "friction", "compare", "diagnose", "report", "sweep")


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``persson`` console script; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "_run", None):
        parser.print_help()
        return 2
    from .errors import InputError as PerssonInputError

    try:
        return int(args._run(args) or 0)
    except (PerssonInputError, ValueError, FileNotFoundError) as exc:
        print(f"persson {args._name}: error: {exc}", file=sys.stderr)
        return 2


def build_parser() -> argparse.ArgumentParser:
    """The argument parser with one sub-command per available command module."""
    from . import __version__

    parser = argparse.ArgumentParser(
        prog="persson",
        description="Rubber friction from Persson's multiscale contact theory: friction, real contact area, "
                    "flash temperature; comparison with measured friction and diagnosis of missing effects.")
    parser.add_argument("--version", action="version", version=f"persson {__version__}")
    sub = parser.add_subparsers(title="commands", metavar="COMMAND")
    for name in COMMANDS:
        try:
            mod = importlib.import_module(f".commands.{name}", __package__)
        except ModuleNotFoundError as exc:
            if exc.name and exc.name.endswith(f"commands.{name}"):
                continue  # command not available in this build
            raise
        p = sub.add_parser(mod.NAME, help=mod.HELP, description=mod.HELP)
        mod.add_arguments(p)
        p.set_defaults(_run=mod.run, _name=mod.NAME)
    return parser


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
