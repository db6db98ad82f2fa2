"""Sweeps: length-scale band studies and parameter grids, run serially, in local processes or on Dask.

Which wavelengths of the road carry the friction, and how friction moves with pressure, q1, temperature or any
model parameter. Every function returns a :class:`Table` (one row per point, inputs and outputs as columns)
that saves to CSV; ``persson sweep CASE ...`` writes the same table.

>>> import surfaces, materials, persson
>>> from persson import sweeps
>>> model = persson.Model(surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e7, hrms=20e-6),
...                       materials.ConstantModulus(5e6, 2e6))
>>> t = sweeps.bands(model, "decades", speed=1.0, pressure=0.3e6)
>>> t.where(mode="restrict")["mu_hysteresis"].round(3)    # one row per decade of q: 1e3..1e4, .., 1e6..1e7
array([0.006, 0.01 , 0.014, 0.019])
>>> t = sweeps.grid(model, {"pressure": "0.1e6:0.9e6:5", "surface.q1": [1e5, 1e6, 1e7]},
...                 speed=[0.01, 0.1, 1.0], scheduler="tcp://scheduler:8786")  # doctest: +SKIP
>>> t.to_csv("results.csv")                                                 # doctest: +SKIP

See :mod:`persson.sweeps.bands` for the two band modes and :mod:`persson.sweeps.params` for parameter names.
"""

from .bands import BAND_KINDS, BandSurface, band_contributions, band_edges, check_bands, continuous_cells
from .core import BAND_MODES, OUTPUTS, bands, effective_q_range, grid
from .execute import Progress, SweepInterrupted
from .params import CONDITIONS, parse_param, parse_values, set_parameter, sweepable
from .table import Table, read_table

__all__ = [
    "bands", "grid", "Table", "read_table", "SweepInterrupted",
    "band_edges", "band_contributions", "check_bands", "continuous_cells", "BandSurface", "effective_q_range",
    "parse_param", "parse_values", "set_parameter", "sweepable",
    "BAND_KINDS", "BAND_MODES", "OUTPUTS", "CONDITIONS", "Progress",
]
