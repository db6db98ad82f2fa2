"""Commands of the ``persson`` command line that belong to the validation loop: ``demo``, ``compare``,
``diagnose``, ``report``.

They are registered through the entry-point group ``persson.commands`` (see ``pyproject.toml``), so the engine's
command line lists them without depending on this package. Each module exposes ``NAME``, ``HELP``,
``add_arguments(parser)`` and ``run(args) -> int``.
"""
