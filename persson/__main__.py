"""``python -m persson`` runs the command line."""

import sys

from .commands.cli import program

sys.exit(program())
