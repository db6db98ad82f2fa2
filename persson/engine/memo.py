"""Memoisation of pure functions of an input object (a surface, a material) for as long as that object lives.

Fits and sweeps call the engine hundreds of times with the same surface and material and only an effect's
parameter changed; the quadrature rule of the PSD and the angular integrals of the modulus are then the same at
every call. They are kept in a dictionary per object, weakly keyed (an entry goes with its object) and bounded
(cleared past :data:`MAX_ENTRIES` keys per object). Only exact repeats are reused: the key holds every argument,
so a result never depends on which calls came before. Inputs are taken as immutable, as the project's surfaces and
materials are (frozen dataclasses).
"""

from __future__ import annotations

import weakref

__all__ = ["per_object", "MAX_ENTRIES"]

#: Entries kept per object before its dictionary is cleared.
MAX_ENTRIES = 32

_MEMO: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()


def per_object(obj, key, compute):
    """``compute()``, memoised under ``key`` for ``obj``.

    Parameters
    ----------
    obj : object
        The input the result is a pure function of (with ``key``). Objects that cannot be weakly referenced or
        hashed are not memoised: ``compute()`` is called every time.
    key : hashable
        Every other argument of the computation.
    compute : callable
        Computes the result; called once per (object, key) while the entry lives.
    """
    try:
        memo = _MEMO.setdefault(obj, {})
    except TypeError:
        return compute()
    value = memo.get(key)
    if value is None:
        if len(memo) >= MAX_ENTRIES:
            memo.clear()
        value = memo[key] = compute()
    return value
