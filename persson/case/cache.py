"""A cache of slow-to-build case objects (master curves fitted to DMA isotherms), keyed by content.

The key is a SHA-256 of: the bytes of every input file (not their names or dates, so a copied or touched file
still hits and an edited one misses), the build options, and the source code of the package that builds the
object (a new version of ``materials`` refits). Entries are pickles in

* ``$PERSSON_CACHE_DIR`` when set, else
* ``$XDG_CACHE_HOME/persson-friction``, else ``~/.cache/persson-friction``,

never inside a folder holding the inputs (if a configured cache folder would be there, nothing is cached). Set
``PERSSON_NO_CACHE=1`` to switch the cache off. A damaged entry is ignored and rebuilt.
"""

from __future__ import annotations

import hashlib
import json
import os
import pickle
import sys
from pathlib import Path
from typing import Callable

__all__ = ["cached", "cache_dir", "cache_key", "CACHE_ENV", "NO_CACHE_ENV"]

CACHE_ENV = "PERSSON_CACHE_DIR"
NO_CACHE_ENV = "PERSSON_NO_CACHE"
_FORMAT = 1  # bump when the entry layout changes


def cache_dir() -> Path | None:
    """The cache folder, or None when caching is switched off."""
    if os.environ.get(NO_CACHE_ENV, "").strip().lower() not in ("", "0", "false", "no"):
        return None
    if os.environ.get(CACHE_ENV):
        return Path(os.environ[CACHE_ENV]).expanduser()
    xdg = os.environ.get("XDG_CACHE_HOME")
    root = Path(xdg).expanduser() if xdg else Path.home() / ".cache"
    return root / "persson-friction"


def cache_key(kind: str, files, options: dict) -> str:
    """SHA-256 (hex) of the kind, the files' bytes (in order), the options and the building code's version."""
    h = hashlib.sha256()
    h.update(f"persson-cache/{_FORMAT}/{kind}/python{sys.version_info[:2]}\n".encode())
    h.update(json.dumps(options, sort_keys=True, default=repr).encode())
    for f in files:
        h.update(b"\0file\0")
        with open(f, "rb") as fh:
            for block in iter(lambda: fh.read(1 << 20), b""):
                h.update(block)
    h.update(_code_fingerprint(kind).encode())
    return h.hexdigest()


def cached(kind: str, files, options: dict, build: Callable, *, notes: list | None = None, inputs=()):
    """``build()``, or its earlier result for the same file contents and options.

    Parameters
    ----------
    kind : str
        What is built (``"master_curve"``); part of the key and of the notes.
    files : sequence of path-like
        The files whose content the result depends on.
    options : dict
        Every option of the build (JSON-serialisable, or with a stable ``repr``).
    build : callable
        Builds the object (picklable).
    notes : list, optional
        Appended with what happened (cache hit, new entry, or why nothing was cached).
    inputs : sequence of path-like
        Input files; the cache is never placed in their folders.
    """
    notes = [] if notes is None else notes
    folder = cache_dir()
    label = kind.replace("_", " ")
    if folder is None:
        return build()
    folder = folder / kind
    if _inside_inputs(folder, [*files, *inputs]):
        notes.append(f"{label}: not cached (the cache folder {folder} lies in a folder of the inputs)")
        return build()
    key = cache_key(kind, files, options)
    entry = folder / f"{key}.pickle"
    if entry.is_file():
        try:
            with open(entry, "rb") as fh:
                obj = pickle.load(fh)
            notes.append(f"{label}: loaded from the cache ({entry}); unchanged inputs and options")
            return obj
        except Exception:  # noqa: BLE001 - a damaged or incompatible entry is rebuilt
            pass
    obj = build()
    try:
        from ..io import atomic_write

        with atomic_write(entry, "wb") as fh:
            pickle.dump(obj, fh, protocol=pickle.HIGHEST_PROTOCOL)
        notes.append(f"{label}: built and cached ({entry})")
    except (OSError, pickle.PicklingError, TypeError, AttributeError) as exc:
        notes.append(f"{label}: built, not cached ({exc})")
    return obj


def _inside_inputs(folder: Path, inputs) -> bool:
    """Whether the cache folder lies in a folder holding inputs (the default ~/.cache location never counts,
    even for inputs somewhere in the home folder)."""
    target = folder.resolve()
    default = (Path.home() / ".cache" / "persson-friction").resolve()
    if target == default or default in target.parents:
        return False
    for f in inputs:
        parent = Path(f).resolve().parent
        if target == parent or parent in target.parents:
            return True
    return False


_FINGERPRINTS: dict[str, str] = {}


def _code_fingerprint(kind: str) -> str:
    """Hash of the source files of the package that builds ``kind`` (materials for master curves)."""
    if kind in _FINGERPRINTS:
        return _FINGERPRINTS[kind]
    import materials

    h = hashlib.sha256(getattr(materials, "__version__", "").encode())
    root = Path(materials.__file__).resolve().parent
    for f in sorted(root.rglob("*.py")):
        h.update(f.relative_to(root).as_posix().encode())
        h.update(f.read_bytes())
    _FINGERPRINTS[kind] = h.hexdigest()
    return _FINGERPRINTS[kind]
