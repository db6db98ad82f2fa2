"""Output files: atomic writing, CSV tables, and the safety rules every command follows.

Rules (see ``docs/conventions.md``, "Output files"):

* a file is written completely or not at all (temporary file in the same folder, then rename);
* an output path that resolves to one of the command's inputs is refused;
* an existing file is overwritten only when asked (``force=True``, the ``--force`` flag);
* the output folder is checked for writability before any computation;
* an interrupted run (an exception or Ctrl-C) leaves the previous outputs untouched and puts what it had
  finished beside them as ``<name>.partial<suffix>``, and says so.

The Python writers (``write_csv``, the ``to_csv`` methods of results, ``validation.write_report``, figure
savers) follow the first three through :func:`check_overwrite`: a file that one of the objects being written was
read from is refused, and an existing file is replaced only with ``overwrite=True``.

:class:`Outputs` implements the last four for a command: its outputs are written into a hidden staging folder
beside their destination and moved into place together when the command succeeds.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import sys
import tempfile
from pathlib import Path

import numpy as np

from .errors import InputError

__all__ = ["atomic_write", "write_csv", "Outputs", "check_output", "check_overwrite", "source_files",
           "check_writable", "partial_path", "free_path"]


@contextlib.contextmanager
def atomic_write(path, mode: str = "w", **kwargs):
    """Open a temporary file beside ``path``; on success rename it to ``path`` (all or nothing).

    The file is written completely or not at all: on an exception the temporary file is removed and an
    existing ``path`` is left untouched.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    os.chmod(tmp, _file_mode())
    try:
        with os.fdopen(fd, mode, **kwargs) as fh:
            yield fh
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


def write_csv(path, columns: dict, comments: tuple[str, ...] = (), *, overwrite: bool = False,
              inputs=()) -> Path:
    """Write equal-length ``columns`` (name -> 1D array or list) as a CSV with a header row, atomically.

    ``path`` may not be one of ``inputs`` (files the data were read from) and may exist only with
    ``overwrite=True`` (:func:`check_overwrite`).
    """
    check_overwrite(path, overwrite=overwrite, inputs=inputs)
    names = list(columns)
    cols = [np.asarray(columns[n]) for n in names]
    n = {c.shape[0] for c in cols}
    if len(n) != 1:
        raise ValueError(f"write_csv: columns of unequal length {sorted(n)}")
    with atomic_write(path, "w", newline="") as fh:
        for c in comments:
            fh.write(f"# {c}\n")
        fh.write(",".join(names) + "\n")
        for row in zip(*cols):
            fh.write(",".join(_fmt(x) for x in row) + "\n")
    return Path(path)


def partial_path(path) -> Path:
    """Where the partial result of an interrupted run goes: ``out.csv`` -> ``out.partial.csv``."""
    path = Path(path)
    return path.with_name(f"{path.stem}.partial{path.suffix}")


def free_path(path) -> Path:
    """``path`` if nothing exists there, else the first free ``<stem>-2<suffix>``, ``<stem>-3<suffix>``, ..."""
    path = Path(path)
    if not path.exists():
        return path
    for i in range(2, 10_000):
        cand = path.with_name(f"{path.stem}-{i}{path.suffix}")
        if not cand.exists():
            return cand
    raise InputError(f"{path}: no free name beside it")  # pragma: no cover - 10 000 siblings


def check_output(path, *, inputs=(), force: bool = False, what: str = "output") -> Path:
    """Check an output file before computing; returns it as a Path.

    Parameters
    ----------
    path : path-like
        The output file.
    inputs : iterable of path-like
        Files the command reads; the output may not be one of them.
    force : bool
        Allow overwriting an existing file.
    what : str
        The option or role named in messages (e.g. ``"-o"``).

    Raises
    ------
    InputError
        The output is one of the inputs, is a folder, exists (without ``force``), or its folder cannot be
        written (naming that folder).
    """
    path = Path(path)
    for inp in inputs:
        if _same_file(path, Path(inp)):
            raise InputError(f"{what} {path}: this is one of the inputs ({Path(inp)}); choose another output "
                             "file (inputs are never overwritten)")
    if path.is_dir():
        raise InputError(f"{what} {path}: is a folder; expected a file name")
    if path.exists() and not force:
        raise InputError(f"{what} {path}: the file exists; pass --force to overwrite it (or choose another name)")
    check_writable(path.parent, what)
    return path


def check_overwrite(path, *, overwrite: bool = False, inputs=(), what: str = "path") -> Path:
    """The rule of every Python writer: never write over an input, nor over an existing file unasked.

    Parameters
    ----------
    path : path-like
        The file about to be written.
    overwrite : bool
        Allow replacing an existing file (never one of ``inputs``).
    inputs : iterable of path-like
        Files the written objects were read from (see :func:`source_files`): refused even with ``overwrite``.
    what : str
        The argument named in messages.

    Raises
    ------
    InputError
        ``path`` is one of ``inputs``, a folder, or an existing file without ``overwrite=True``.
    """
    path = Path(path)
    for inp in inputs:
        if _same_file(path, Path(inp)):
            raise InputError(f"{what} {path}: this file is an input of what is being written ({Path(inp)}); "
                             "choose another file name (inputs are never overwritten)")
    if path.is_dir():
        raise InputError(f"{what} {path}: is a folder; expected a file name")
    if path.exists() and not overwrite:
        raise InputError(f"{what} {path}: the file exists; pass overwrite=True to replace it (or choose another "
                         "name)")
    return path


def source_files(*objects) -> tuple[Path, ...]:
    """The existing files that ``objects`` were read from: their ``inputs`` (a case), ``source`` (a table read from
    a file), and those of their ``spec``, ``case``, ``measurements``, ``model``, ``surface`` and ``material``, one
    level deep. Lists, tuples and sets are searched too. For :func:`check_overwrite`'s ``inputs``."""
    out: list[Path] = []

    def add(value):
        if isinstance(value, (str, Path)):
            try:
                p = Path(value)
                if p.is_file():
                    out.append(p)
            except (OSError, ValueError):
                pass

    def visit(obj, depth):
        if obj is None or isinstance(obj, (str, bytes, int, float)):
            return
        if isinstance(obj, (list, tuple, set, frozenset)):
            for o in obj:
                visit(o, depth)
            return
        inputs = _attribute(obj, "inputs")
        if isinstance(inputs, (list, tuple)):
            for p in inputs:
                add(p)
        add(_attribute(obj, "source"))
        add(_attribute(obj, "path"))
        if depth < 2:
            for attr in ("spec", "case", "measurements", "model", "surface", "material", "steps"):
                visit(_attribute(obj, attr), depth + 1)

    visit(objects, 0)
    return tuple(dict.fromkeys(out))


def check_writable(folder, what: str = "output") -> Path:
    """Check that files can be created in ``folder`` (or in the nearest existing folder above it, where the
    missing folders will be made). Raises InputError naming the folder."""
    folder = Path(folder) if str(folder) else Path(".")
    probe = folder
    while not probe.exists():
        if probe.parent == probe:
            break
        probe = probe.parent
    if not probe.is_dir():
        raise InputError(f"{what}: cannot create the folder {folder}: {probe} is a file")
    try:
        fd, tmp = tempfile.mkstemp(prefix=".persson-write-test-", dir=probe)
    except OSError as exc:
        where = folder if probe == folder else f"{folder} (its existing parent {probe})"
        raise InputError(f"{what}: the folder {where} is not writable ({exc.strerror or exc})") from None
    os.close(fd)
    os.unlink(tmp)
    return folder


class Outputs:
    """The output files of one command: checked before computing, written together or not at all.

    Parameters
    ----------
    command : str
        Named in messages (e.g. ``"persson sweep"``).
    inputs : iterable of path-like
        Files the command reads (never overwritten).
    force : bool
        Allow overwriting existing outputs.
    stream : file, optional
        Where the notes on an interrupted run go (default ``sys.stderr``).

    Examples
    --------
    >>> import pathlib, shutil, tempfile
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> with Outputs("persson friction", inputs=[folder / "case.toml"], force=False) as out:
    ...     csv = out.file(folder / "result.csv", what="-o")    # checked now; write to ``csv``
    ...     _ = csv.write_text("speed_m_s,mu\\n1.0,0.8\\n")     # compute, then write
    >>> [p.name for p in out.written], (folder / "result.csv").read_text().splitlines()[1]
    (['result.csv'], '1.0,0.8')
    >>> shutil.rmtree(folder)

    Writers receive a staging path (a hidden folder beside the destination); on success every staged file is
    renamed to its destination, on an exception or Ctrl-C to ``<name>.partial<suffix>`` beside it, the
    destination keeping its previous content.
    """

    def __init__(self, command: str, *, inputs=(), force: bool = False, stream=None):
        self.command = command
        self.inputs = tuple(Path(p) for p in inputs)
        self.force = bool(force)
        self.stream = stream
        self.written: list[Path] = []
        self.partial: list[Path] = []
        self._staging: dict[Path, Path] = {}       # destination folder -> staging folder
        self._files: dict[Path, Path] = {}         # staged file -> destination file
        self._folders: list[tuple[Path, Path]] = []  # (staging folder, destination folder) of free-form outputs
        self._made: list[Path] = []                # destination folders this object created
        self._reserved: list[Path] = []            # partial files a computation may write itself

    def __enter__(self) -> "Outputs":
        return self

    def __exit__(self, exc_type, exc, tb) -> bool:
        if exc_type is None:
            self.commit()
        else:
            self.abort(interrupted=issubclass(exc_type, KeyboardInterrupt))
        return False

    # ----------------------------------------------------------------------------------------------------
    def file(self, path, what: str = "output") -> Path:
        """Register the output file ``path`` (checked now); returns the staging path to write it to."""
        dest = check_output(path, inputs=self.inputs, force=self.force, what=what)
        staged = self._stage_dir(dest.parent) / dest.name
        if staged in self._files:
            raise InputError(f"{what} {dest}: given twice as an output")
        self._files[staged] = dest
        return staged

    def folder(self, path, names=(), patterns=(), what: str = "output folder") -> Path:
        """Register an output folder whose files a writer names itself; returns the staging folder.

        ``names`` (file names) and ``patterns`` (glob patterns such as ``"case_*.png"``) are the files it will
        write: existing ones are refused without ``force`` now, before computing.
        """
        dest = Path(path)
        if dest.exists() and not dest.is_dir():
            raise InputError(f"{what} {dest}: is a file; expected a folder")
        check_writable(dest, what)
        for name in names:
            check_output(dest / name, inputs=self.inputs, force=self.force, what=what)
        if not self.force and dest.is_dir():
            for pattern in patterns:
                found = sorted(dest.glob(pattern))
                if found:
                    raise InputError(f"{what} {dest}: {found[0].name} exists; pass --force to overwrite the "
                                     "outputs of an earlier run (or choose another folder)")
        staged = self._stage_dir(dest)
        self._folders.append((staged, dest))
        return staged

    def commit(self) -> list[Path]:
        """Move every staged file into place; returns the destinations (also in ``written``)."""
        try:
            for staged, dest in self._staged_files():
                if any(_same_file(dest, p) for p in self.inputs):  # a free-form writer named an input
                    raise InputError(f"{self.command}: refusing to overwrite the input {dest}")
                os.replace(staged, dest)
                self.written.append(dest)
        except BaseException:
            self.abort(interrupted=False)
            raise
        self._cleanup()
        return list(self.written)

    def abort(self, interrupted: bool = True) -> list[Path]:
        """Keep the destinations as they were; move staged files beside them as ``*.partial*`` and say so."""
        for staged, dest in self._staged_files():
            target = self._partial_target(dest)
            with contextlib.suppress(OSError):
                os.replace(staged, target)
                self.partial.append(target)
        self.partial += [p for p in self._reserved if p.is_file() and p not in self.partial]
        self._cleanup()
        why = "interrupted" if interrupted else "stopped by an error"
        stream = self.stream if self.stream is not None else sys.stderr
        for target in self.partial:
            print(f"{self.command}: {why}; partial result written to {target.resolve()} (the previous "
                  f"{_strip_partial(target).name}, if any, is unchanged)", file=stream)
        return list(self.partial)

    def partial_for(self, path) -> Path:
        """Where a computation may write its own partial result for the output ``path`` if it stops early
        (e.g. :func:`persson.sweeps.grid`'s ``partial=``); an interrupted run reports it when it exists."""
        target = self._partial_target(Path(path))
        self._reserved.append(target)
        return target

    # ----------------------------------------------------------------------------------------------------
    def _stage_dir(self, dest_folder: Path) -> Path:
        key = dest_folder.resolve() if dest_folder.exists() else dest_folder.absolute()
        if key not in self._staging:
            missing = [p for p in (dest_folder, *dest_folder.parents) if not p.exists()]
            dest_folder.mkdir(parents=True, exist_ok=True)
            self._made.extend(missing)
            self._staging[key] = Path(tempfile.mkdtemp(prefix=".persson-staging-", dir=dest_folder))
        return self._staging[key]

    def _staged_files(self):
        pairs = [(s, d) for s, d in self._files.items() if s.exists()]
        for staged_dir, dest in self._folders:
            for f in sorted(staged_dir.iterdir()) if staged_dir.is_dir() else ():
                if f.is_file() and f not in self._files:
                    pairs.append((f, dest / f.name))
        return pairs

    def _partial_target(self, dest: Path) -> Path:
        return partial_path(dest) if self.force else free_path(partial_path(dest))

    def _cleanup(self) -> None:
        for d in self._staging.values():
            shutil.rmtree(d, ignore_errors=True)
        for d in self._made:  # folders made for outputs that never came: leave no empty trace
            with contextlib.suppress(OSError):
                d.rmdir()
        self._made.clear()
        self._reserved.clear()
        self._staging.clear()
        self._files.clear()
        self._folders.clear()


def _attribute(obj, name: str):
    try:
        return getattr(obj, name, None)
    except Exception:  # noqa: BLE001 - a property that cannot be computed names no file
        return None


def _same_file(a: Path, b: Path) -> bool:
    try:
        if a.exists() and b.exists():
            return os.path.samefile(a, b)
    except OSError:
        pass
    return a.resolve() == b.resolve()


def _strip_partial(path: Path) -> Path:
    stem = path.stem
    base = stem.rsplit(".partial", 1)[0]
    return path.with_name(base + path.suffix)


def _fmt(x) -> str:
    if isinstance(x, (float, np.floating)):
        return repr(float(x))
    return str(x)


def _file_mode() -> int:
    # mkstemp creates 0600 files; give the final file the permissions open() would (0666 minus the umask).
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask
