"""Progress feedback for long work: a status line on stderr, never on stdout.

The protocol a library function accepts as ``progress=`` is any callable; it is called with a short status
text, ``progress("fitting WLF constants")``, a text and the fraction of the work done (or None),
``progress("shifting isotherms", 0.4)`` (the form of :func:`materials.master_curve`), counts,
``progress(done, total)`` (the form of :func:`persson.sweeps.grid`), or a text and counts,
``progress("isotherm", done, total)``. :class:`StatusLine` accepts all four, so the command line passes one object
to every library call.

For work that reports nothing while it runs, :meth:`StatusLine.phase` keeps a ticker alive: the elapsed time is
redrawn in place on a terminal and written as a line every ``log_interval_s`` to a log, so a long silent fit
still shows that it is working.

Output goes to ``sys.stderr``, so ``--json -`` or CSV written to stdout stay clean.
"""

from __future__ import annotations

import contextlib
import sys
import threading
import time
from typing import Callable, Protocol

__all__ = ["ProgressCallback", "StatusLine", "report", "silent"]


class ProgressCallback(Protocol):
    """What a ``progress=`` argument is called with: a text, counts, or both."""

    def __call__(self, *args) -> None:  # pragma: no cover - protocol
        ...


def report(progress: Callable | None, *args) -> None:
    """Call ``progress(*args)`` when a callback was given (the library side of the protocol)."""
    if progress is not None:
        progress(*args)


def silent(*args) -> None:
    """A progress callback that ignores everything."""


class StatusLine:
    """A one-line status display on stderr (redrawn in place on a terminal, throttled lines in a log).

    Parameters
    ----------
    label : str
        Prefix of every line (e.g. ``"persson diagnose"``).
    stream : file, optional
        Default ``sys.stderr`` at the time of each write.
    enabled : bool
        False makes every call a no-op (``--quiet``).
    delay_s : float
        A :meth:`phase` shows up only once it has run this long (quick work stays silent).
    tick_s : float
        How often a running :meth:`phase` redraws its elapsed time on a terminal.
    log_interval_s : float
        At most one line per this many seconds on a non-terminal stream (except phase starts and ends).
    """

    def __init__(self, label: str, stream=None, *, enabled: bool = True, delay_s: float = 1.0,
                 tick_s: float = 0.5, log_interval_s: float = 10.0):
        self.label = label
        self._stream = stream
        self.enabled = bool(enabled)
        self.delay_s = float(delay_s)
        self.tick_s = float(tick_s)
        self.log_interval_s = float(log_interval_s)
        self._lock = threading.Lock()
        self._phase: str | None = None
        self._phase_start = 0.0
        self._phase_shown = False
        self._detail = ""
        self._last_line = -float("inf")
        self._open = False  # a line drawn in place and not yet ended
        self.lines: list[str] = []  # every status text shown (for tests and logs)

    @property
    def stream(self):
        """The stream written to: the one given, else ``sys.stderr`` at the time of the call."""
        return self._stream if self._stream is not None else sys.stderr

    @property
    def tty(self) -> bool:
        """Whether :attr:`stream` is a terminal (its ``isatty()``; False when it has none)."""
        return bool(getattr(self.stream, "isatty", lambda: False)())

    # ----------------------------------------------------------------------------------------------------
    def __call__(self, *args) -> None:
        """``status(text)``, ``status(text, fraction)``, ``status(done, total)`` or ``status(text, done, total)``."""
        if not self.enabled or not args:
            return
        text, counts = "", ()
        if isinstance(args[0], str):
            text, counts = args[0], tuple(c for c in args[1:] if c is not None)
        else:
            counts = args
        if len(counts) >= 2 and counts[1]:
            done, total = counts[0], counts[1]
            text = (text + " " if text else "") + f"{done}/{total} ({100 * done / total:.0f} %)"
        elif counts:  # a fraction of the work done
            text = (text + " " if text else "") + f"({100 * float(counts[0]):.0f} %)"
        with self._lock:
            self._detail = text
            if self._phase is None or self._phase_shown:
                self._show(force=not self.tty and self._phase is None)

    @contextlib.contextmanager
    def phase(self, text: str):
        """Show ``text`` with a running clock while the block runs; ends with the time it took."""
        if not self.enabled:
            yield self
            return
        with self._lock:
            self._phase, self._phase_start, self._detail = text, time.monotonic(), ""
            self._phase_shown = False
        stop = threading.Event()
        ticker = threading.Thread(target=self._tick, args=(stop,), daemon=True)
        ticker.start()
        ok = False
        try:
            yield self
            ok = True
        finally:
            stop.set()
            ticker.join()
            with self._lock:
                elapsed = time.monotonic() - self._phase_start
                if self._phase_shown:
                    self._detail = f"done in {elapsed:.1f} s" if ok else f"stopped after {elapsed:.1f} s"
                    self._show(force=True)
                    self._end_line()
                self._phase = None
                self._detail = ""

    def echo(self, text: str, file=None) -> None:
        """Print ``text`` (default to stdout) without tearing a status line drawn in place on the terminal."""
        with self._lock:
            if self._open:
                with contextlib.suppress(OSError, ValueError):
                    self.stream.write("\r\033[K")
                    self.stream.flush()
                self._open = False
            print(text, file=file or sys.stdout, flush=True)

    def close(self) -> None:
        """End a line drawn in place."""
        with self._lock:
            self._end_line()

    # ----------------------------------------------------------------------------------------------------
    def _tick(self, stop: threading.Event) -> None:
        while not stop.wait(min(self.tick_s, self.delay_s)):
            with self._lock:
                if not self._phase_shown:
                    if time.monotonic() - self._phase_start < self.delay_s:
                        continue
                    self._phase_shown = True
                    self._show(force=True)
                else:
                    self._show(force=False)

    def _show(self, force: bool) -> None:
        now = time.monotonic()
        # a log gets a line every log_interval_s for the first minute of a phase, then every 3 log_interval_s
        interval = self.log_interval_s * (3 if self._phase is not None and now - self._phase_start > 60 else 1)
        if not force and not self.tty and now - self._last_line < interval:
            return
        parts = [self.label + ":"]
        if self._phase is not None:
            parts.append(self._phase)
            parts.append(f"({now - self._phase_start:.0f} s)")
        if self._detail:
            parts.append("- " + self._detail if self._phase is not None else self._detail)
        text = " ".join(parts)
        self.lines.append(text)
        self._last_line = now
        try:
            if self.tty:
                self.stream.write("\r\033[K" + text)
                self._open = True
            else:
                self.stream.write(text + "\n")
            self.stream.flush()
        except (OSError, ValueError):  # a closed or broken stream must not stop the computation
            self.enabled = False

    def _end_line(self) -> None:
        if self._open:
            with contextlib.suppress(OSError, ValueError):
                self.stream.write("\n")
                self.stream.flush()
            self._open = False
