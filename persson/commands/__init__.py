"""Sub-commands of the ``persson`` command line (one module each: NAME, HELP, add_arguments, run)."""
