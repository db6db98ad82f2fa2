"""The engine's sub-commands of the ``persson`` command line (one module each: NAME, HELP, add_arguments, run).

Commands of other packages are found through the entry-point group ``persson.commands`` (see
:mod:`persson.commands.cli`); :mod:`persson.commands._common` holds what every command shares.
"""
