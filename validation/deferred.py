"""Values computed on first use, and frozen-dataclass fields that hold them.

The profile-likelihood intervals of a fit (:func:`validation.refit.with_uncertainty`) cost more model evaluations
than the fit itself where the likelihood is not quadratic. The search over sets of effects (:mod:`validation.select`)
fits many sets whose intervals nobody reads: only the sets it reports, and those whose credibility depends on an
interval (a parameter on a search bound or outside its plausible range), need them. Their fits therefore carry the
intervals as a :class:`Deferred`, and the fields that hold them (:class:`Lazy`) compute it when first read: the
value is the same as if it had been computed at once (the same fitter, from the same optimum, with the same
evaluations allowed), only later or never.
"""

from __future__ import annotations

from dataclasses import MISSING

__all__ = ["Deferred", "Lazy", "is_ready", "raw"]


class Deferred:
    """A value computed once, when first asked for.

    Parameters
    ----------
    compute : callable
        Called without arguments, once; its result is kept.
    """

    __slots__ = ("_compute", "_value")

    def __init__(self, compute):
        self._compute = compute
        self._value = None

    def __call__(self):
        """The value (computed now if it has not been yet)."""
        if self._compute is not None:
            compute, self._compute = self._compute, None
            self._value = compute()
        return self._value

    @property
    def ready(self) -> bool:
        """Whether the value has been computed."""
        return self._compute is None

    def part(self, index) -> "Deferred":
        """A :class:`Deferred` of ``value[index]`` (computing this one when first asked for)."""
        return Deferred(lambda: self()[index])

    def __reduce__(self):
        # pickling (or deep-copying) reads the value: the computation is a closure, which no pickle can hold
        return _computed, (self(),)


def _computed(value) -> Deferred:
    """A :class:`Deferred` that holds ``value`` already (how a pickled one is restored)."""
    d = Deferred(None)
    d._value = value
    return d


class Lazy:
    """Descriptor of a frozen dataclass's field whose value may be given as a :class:`Deferred`: the first read
    computes it and keeps the result in its place. Any other value is stored and read as it is.

    Parameters
    ----------
    default : object, optional
        The field's default value (none: the field is required).
    """

    def __init__(self, default=MISSING):
        self.default = default

    def __set_name__(self, owner, name):
        self.name = name
        self.slot = "_lazy_" + name

    def __get__(self, obj, owner=None):
        if obj is None:
            # dataclasses read the class attribute to find the field's default
            if self.default is MISSING:
                raise AttributeError(self.name)
            return self.default
        value = obj.__dict__[self.slot]
        if isinstance(value, Deferred):
            value = value()
            obj.__dict__[self.slot] = value
        return value

    def __set__(self, obj, value):
        # reached through object.__setattr__ in the frozen dataclass's __init__ only
        obj.__dict__[self.slot] = value


def is_ready(obj, name: str) -> bool:
    """Whether the field ``name`` of ``obj`` (a :class:`Lazy` one, or any attribute) holds its value already."""
    value = obj.__dict__.get("_lazy_" + name)
    return not isinstance(value, Deferred) or value.ready


def raw(obj, name: str):
    """The value of the field ``name`` of ``obj`` as stored: a :class:`Deferred` not computed yet stays one (to hand
    it on to another object without computing it)."""
    slot = "_lazy_" + name
    return obj.__dict__[slot] if slot in obj.__dict__ else getattr(obj, name)
