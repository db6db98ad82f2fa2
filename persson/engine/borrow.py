"""Borrowed views of a kernel's arguments: the same arrays without their reference count.

numba counts the references of every array it binds to a variable, an argument of a function it calls included
(and every array field of a named tuple it passes on), with an atomic increment and decrement of the array's
meminfo. In the kernels' innermost loops (an interpolation in the patch-heating lattice at every patch node, the
contact weights at every wavevector node) these atomic operations took about 30 % of the heated patch's march and
12 % of the friction and flash-temperature kernels' time (sampled with ``perf`` on the kernels' calls of a
diagnosis), and an atomic operation costs more where two threads count the same array (its counter's cache line
then moves between the cores).

:func:`borrowed` hands a kernel its arguments' arrays as views with no meminfo, which numba's reference counting
skips (``NRT_incref`` of a null meminfo returns at once). That is safe for the arrays a kernel receives as
arguments: its caller holds them until the kernel returns, and a view never outlives the call. An array the kernel
allocates itself may be borrowed only while the variable that owns it is used later on (numba frees an array
after the last use of its variable, and the view alone does not hold it): the patch-heating march allocates its
work arrays once per thread, hands the rows borrowed views and reads the arrays' sizes after the last row
(:func:`persson.slip.heating_kernels._march_all`); counted, those arrays took 60 % of the march.

numba's on-disk cache keys a compiled kernel by its own source file: a change to this module does not reach the
kernels that use it (``persson/engine/kernels.py``, ``persson/slip/heating_kernels.py``) until their files change
too (or their cache is cleared).
"""

from __future__ import annotations

from numba.core import cgutils, types
from numba.extending import intrinsic, overload

__all__ = ["borrowed"]


def borrowed(value):
    """``value`` (an array, or a tuple or named tuple of arrays and scalars, nested or not) with every array
    replaced by a view of the same data, shape and strides that holds no reference (null meminfo and parent).

    Only for arrays the kernel's caller holds for the whole call (the kernel's own arguments); see the module
    docstring. Called from Python (or in a kernel run with ``NUMBA_DISABLE_JIT=1``) it returns ``value`` itself:
    the interpreter counts no references of its own.

    Parameters
    ----------
    value : ndarray or tuple
        The kernel's arguments.

    Returns
    -------
    ndarray or tuple
        The same, of the same numba type.
    """
    return value


@overload(borrowed)
def _borrowed_compiled(value):
    return lambda value: _without_meminfo(value)


@intrinsic
def _without_meminfo(typingctx, value):
    def codegen(context, builder, signature, args):
        return _strip(context, builder, signature.args[0], args[0])

    return value(value), codegen


def _strip(context, builder, typ, val):
    """LLVM value ``val`` of numba type ``typ`` with the meminfo and parent of every array in it set to null."""
    if isinstance(typ, types.Array):
        ary = context.make_array(typ)(context, builder, value=val)
        ary.meminfo = cgutils.get_null_value(ary.meminfo.type)
        ary.parent = cgutils.get_null_value(ary.parent.type)
        return ary._getvalue()
    if isinstance(typ, types.BaseTuple):
        for i, member in enumerate(typ):
            item = builder.extract_value(val, i)
            val = builder.insert_value(val, _strip(context, builder, member, item), i)
        return val
    return val
