"""Case files (``case.toml``): one study bound together.

:mod:`~persson.case.schema` declares every section and key (types, units, documentation);
:mod:`~persson.case.loader` reads and checks a file and builds the model; :mod:`~persson.case.cache` keeps master
curves fitted from DMA isotherms between runs.
"""

from .loader import (CaseFile, CaseSpec, build_material, build_surface, parse_case, read_case, resolve_case,
                     shipped_cases)

__all__ = ["CaseSpec", "CaseFile", "read_case", "parse_case", "resolve_case", "shipped_cases", "build_surface",
           "build_material"]
