"""Commands of the ``persson`` command line that belong to the validation loop: ``demo``, ``compare``,
``diagnose``, ``report``.

They are registered through the entry-point group ``persson.commands`` (see ``pyproject.toml``), so the engine's
command line lists them without depending on this package. Each module exposes ``NAME``, ``HELP``,
``add_arguments(parser)`` and ``run(args) -> int``.
"""


def warm_patch_kernel(case, candidates=None) -> bool:
    """Start compiling the heated patch's kernel in a second process (:func:`persson.warmup.start`, a first run
    only) when this run will use it: the case has a contact patch, and patch heating is in its model or among the
    ``candidates`` (None: every registered effect). Returns whether a process was started."""
    if case.contact is None:
        return False
    if "patch_heating" not in case.model.effect_names and candidates is not None \
            and "patch_heating" not in candidates:
        return False
    from persson import warmup

    return warmup.start()
