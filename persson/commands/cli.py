"""Command line: ``persson <command> ...`` (also ``python -m persson``).

Each command is a module exposing ``NAME``, ``HELP``, ``add_arguments(parser)`` and ``run(args) -> int``. The
engine's own commands live in :mod:`persson.commands` (:data:`COMMANDS`); other installed packages add commands
through the entry-point group ``persson.commands`` (name = "module"), which is how the validation package
contributes ``demo``, ``compare``, ``diagnose`` and ``report`` without the engine depending on it. This module
only discovers and dispatches.

Every command prints where its output went; status lines and warnings go to stderr, so output written to stdout
(``--json -``) stays clean. Exit status: 0 success, 2 bad input, 130 interrupted (Ctrl-C).
"""

from __future__ import annotations

import argparse
import gc
import importlib
import sys
import warnings

__all__ = ["main", "program", "build_parser", "available_commands", "COMMANDS", "COMMANDS_GROUP"]

#: The engine's command modules (in ``persson.commands``).
COMMANDS = ("friction", "sweep", "contact", "tread")
#: Entry-point group through which installed packages add commands.
COMMANDS_GROUP = "persson.commands"
# the order ``--help`` lists the commands in (others follow alphabetically)
_HELP_ORDER = ("demo", "friction", "contact", "compare", "diagnose", "report", "sweep", "tread")


def program() -> int:
    """The ``persson`` program (the console script and ``python -m persson``): :func:`main` on ``sys.argv``;
    returns the exit status.

    The process ends with the command, so what exists when it starts (the imported modules) and when it ends
    lives until then: both are moved out of the garbage collector's sight (:func:`gc.freeze`). The interpreter's
    shutdown otherwise runs full collections over every object left -- some 150 000 after a diagnosis, most of
    them numba's, scipy's and numpy's -- which took 0.3 s of a 3.7 s ``persson diagnose``; the collections during
    the command skip the modules too. A frozen object is still freed by its reference count; only cycles among
    them are left for the process's exit to release. While the command runs, the oldest generation is collected a
    hundred times less often (its threshold 1000 instead of 10 collections of the middle one): each of its
    collections walks every object the command's imports and results have made (matplotlib's import and a
    report's figures set off four of them in ``persson demo``, 0.25-0.5 s), while the young generations, collected
    as usual, free the cycles a command makes and drops. :func:`main`, for calls from Python, leaves the collector
    alone.
    """
    thresholds = gc.get_threshold()
    gc.freeze()
    gc.set_threshold(thresholds[0], thresholds[1], max(thresholds[2], _OLDEST_THRESHOLD))
    try:
        return main()
    finally:
        gc.freeze()
        gc.set_threshold(*thresholds)


#: Collections of the middle generation between two of the oldest while the ``persson`` program runs a command
#: (:func:`program`; Python's default is 10).
_OLDEST_THRESHOLD = 1000


def main(argv: list[str] | None = None) -> int:
    """Run one command (``argv``: the words after ``persson``; default ``sys.argv[1:]``); returns the exit
    status. The console script runs :func:`program`."""
    argv = sys.argv[1:] if argv is None else list(argv)
    # only the named command's module is imported (importing them all costs about 1 s at start-up); help and
    # unknown names get the full parser
    parser = build_parser(only=argv[0] if argv and not argv[0].startswith("-") else None)
    args = parser.parse_args(argv)
    if not getattr(args, "_run", None):
        parser.print_help()
        return 2
    name = args._name
    with warnings.catch_warnings():
        warnings.showwarning = _show_warning(name)
        try:
            return int(args._run(args) or 0)
        except KeyboardInterrupt:
            print(f"persson {name}: interrupted", file=sys.stderr)
            return 130
        except (ValueError, OSError) as exc:  # every package's InputError is a ValueError
            print(f"persson {name}: error: {_message(exc)}", file=sys.stderr)
            return 2


def build_parser(only: str | None = None) -> argparse.ArgumentParser:
    """The argument parser with one sub-command per available command module.

    Parameters
    ----------
    only : str, optional
        Build the sub-command of this name alone when it exists (faster start-up); otherwise all of them.
    """
    from .. import __version__

    parser = argparse.ArgumentParser(
        prog="persson",
        description="Rubber friction from Persson's multiscale contact theory: friction, real contact area, "
                    "flash temperature; comparison with measured friction and diagnosis of missing effects.")
    parser.add_argument("--version", action="version", version=f"persson {__version__}")
    sub = parser.add_subparsers(title="commands", metavar="COMMAND")
    for name, mod in available_commands(only=only).items():
        p = sub.add_parser(mod.NAME, help=mod.HELP, description=mod.HELP)
        mod.add_arguments(p)
        p.set_defaults(_run=mod.run, _name=mod.NAME)
    return parser


def available_commands(only: str | None = None) -> dict:
    """Command name -> module: the engine's own, then those of installed packages, in help order.

    With ``only`` naming an available command, that command's module alone is imported and returned.
    """
    if only is not None:
        one = _one_command(only)
        if one is not None:
            return {only: one}
    found: dict = {}
    for name in COMMANDS:
        try:
            found[name] = importlib.import_module(f".{name}", __package__)
        except ModuleNotFoundError as exc:
            if exc.name and exc.name.endswith(f"commands.{name}"):
                continue  # command not available in this build
            raise
    for ep in _entry_points():
        if ep.name in found:
            continue
        try:
            found[ep.name] = importlib.import_module(ep.value.split(":")[0])
        except ImportError as exc:  # a broken plug-in must not take the engine's commands down
            print(f"persson: command {ep.name!r} from {ep.value} is unavailable ({exc})", file=sys.stderr)
    order = {n: i for i, n in enumerate(_HELP_ORDER)}
    return dict(sorted(found.items(), key=lambda kv: (order.get(kv[0], len(order)), kv[0])))


def _one_command(name: str):
    """The module of command ``name``, or None when no engine command or entry point has that name."""
    if name in COMMANDS:
        return importlib.import_module(f".{name}", __package__)
    for ep in _entry_points():
        if ep.name == name:
            try:
                return importlib.import_module(ep.value.split(":")[0])
            except ImportError:
                return None  # the full listing reports the broken plug-in
    return None


def _entry_points():
    from importlib.metadata import entry_points

    return list(entry_points(group=COMMANDS_GROUP))


def _message(exc: BaseException) -> str:
    if isinstance(exc, OSError) and exc.filename:
        return f"{exc.filename}: {exc.strerror or exc}"
    return str(exc)


def _show_warning(name: str):
    def show(message, category, filename, lineno, file=None, line=None):
        print(f"persson {name}: warning ({category.__name__}): {message}", file=file or sys.stderr)

    return show


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
