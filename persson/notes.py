"""Notes on results: the sentence a reader needs, with a machine-readable kind beside it.

A result's ``notes`` are a tuple of :class:`Note`, each a ``str`` (so ``"extrapolated" in note``, printing and
writing work as for any text) that also carries a ``kind``, the way scipy's ``OptimizeResult`` gives a status
code beside its message: scripts and tests check the kind, not a sentence that may be reworded.

Kinds (:data:`KINDS`):

``"accuracy"``
    the numbers may be less accurate than asked: an error estimate above the tolerance, a table read at its edge;
``"convergence"``
    an iteration stopped before its tolerance, or ran out of the range it was given;
``"extrapolated"``
    an input is used beyond the range it was measured over (a PSD tail past q_r, a shift law far above the
    isotherms);
``"assumed"``
    the computation chose a value the inputs did not give (e.g. the macro-asperity scale of a PSD without roll-off);
``"physics"``
    the result lies where the theory's assumptions are strained (rms slope far above 1, mu above 3, no roughness);
``"input"``
    a fact about how the inputs were used (a PSD cut by an effect, an effect that does not act on this result).

A note that accompanies a warning has the kind of the warning's category (:func:`kind_of_warning`).

Examples
--------
>>> n = Note("PSD tail extrapolated", "extrapolated")
>>> n.kind, "tail" in n, n == "PSD tail extrapolated"
('extrapolated', True, True)
>>> kinds(("plain text", n))
(None, 'extrapolated')
"""

from __future__ import annotations

import numpy as np

from .errors import AccuracyWarning, ConvergenceWarning, InputError, PhysicsWarning

__all__ = ["Note", "KINDS", "kinds", "kind_of", "kind_of_warning", "share_span"]

#: The kinds a :class:`Note` may have.
KINDS = ("accuracy", "convergence", "extrapolated", "assumed", "physics", "input")


class Note(str):
    """A note on a result: its text (this ``str``) and its ``kind``, one of :data:`KINDS`.

    Parameters
    ----------
    text : str
        The sentence a reader needs.
    kind : str
        One of :data:`KINDS`.

    Raises
    ------
    InputError
        If ``kind`` is not one of :data:`KINDS`.
    """

    def __new__(cls, text: str, kind: str):
        if kind not in KINDS:
            raise InputError(f"kind: expected one of {list(KINDS)}, got {kind!r}")
        note = super().__new__(cls, text)
        note._kind = kind
        return note

    @property
    def kind(self) -> str:
        """What the note is about, one of :data:`KINDS`."""
        return self._kind

    def __reduce__(self):
        # str's own reduction would drop the kind; pickles of older results (plain str notes) load unchanged
        return (Note, (str(self), self._kind))


def kind_of(note) -> str | None:
    """The kind of ``note``: a :class:`Note`'s ``kind``, None for plain text (notes of older pickles or of a user's
    ``transform_result``)."""
    return getattr(note, "kind", None)


def kinds(notes) -> tuple:
    """The kind of every note in ``notes`` (None for plain text), in order."""
    return tuple(kind_of(n) for n in notes)


def kind_of_warning(category: type) -> str:
    """The note kind that goes with a warning category: accuracy, convergence, physics, and input for the unit
    checks (``UnitWarning``) and any other category."""
    for cls, kind in ((AccuracyWarning, "accuracy"), (ConvergenceWarning, "convergence"),
                      (PhysicsWarning, "physics")):
        if isinstance(category, type) and issubclass(category, cls):
            return kind
    return "input"


def share_span(share) -> str:
    """A share per speed as the percentage a note quotes: one value when they agree within half a per cent
    (``"42%"``), else their range (``"12%-42%"``)."""
    a = np.atleast_1d(np.asarray(share, dtype=float))
    top = float(np.max(a))
    return f"{top:.0%}" if a.size == 1 or np.ptp(a) < 0.005 else f"{float(np.min(a)):.0%}-{top:.0%}"
