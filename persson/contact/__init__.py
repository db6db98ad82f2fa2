"""Contact mechanics alone: real contact area, interfacial separation, elastic energy and penetration depth
against the nominal pressure.

:mod:`~persson.contact.corrections` (area corrections of Persson's theory and the separation kernel),
:mod:`~persson.contact.separation` (mean interfacial separation, penetration depth, excited layer) and
:mod:`~persson.contact.mechanics` (:func:`contact`, the public entry point).
"""

from .mechanics import ContactResult, contact

__all__ = ["contact", "ContactResult"]
