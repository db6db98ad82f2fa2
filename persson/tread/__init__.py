"""The tyre on the road: a patterned tread of viscoelastic elements driven over measured road profiles.

The element tool of "Tire/pavement friction: presentation of a comprehensive physical tool through advanced contact
modelling" (the element model of M. Kane and co-workers, IFSTTAR, Nantes; with water: Kane et al., Int. J. Pavement
Eng. (2017), doi:10.1080/10298436.2017.1369776), with the local friction of the scales the profiles cannot see from
the Persson engine. Step 1, :class:`Tire`: the static footprint from the tyre's size, load and
inflation. Step 2, :func:`simulate`: the tread (a row of Kelvin elements per road profile, grooves taken out) is
marched over the road at a slip ratio and speed; :func:`slip_map` gives mu(slip, speed) with the ABS peak and the
locked wheel, :func:`rank_surfaces` ranks roads and correlates the ranking with measurements. Wet roads:
:class:`Water` (pseudo-hydrodynamic bearing). Plots in :mod:`persson.tread.plots`; the command ``persson tread``.

Typical use::

    import persson, surfaces, materials
    tire = persson.tread.Tire(diameter=0.63, width=0.205, load=4000.0, inflation_pressure=2.2e5,
                              tread_depth=8e-3, grooves=persson.tread.Grooves(width=8e-3, pitch=30e-3))
    road = surfaces.read_profiles("scans.csv")
    r = persson.tread.simulate(tire, road, materials.example_tread(), speed=16.7, slip=1.0, temperature=20.0)
    r.mu, r.mu_std
    m = persson.tread.slip_map(tire, road, materials.example_tread(), slips=[0.05, 0.1, 0.2, 1.0],
                               speeds=[8.3, 16.7])
    m.peak_mu, m.peak_slip, m.locked_mu
"""

from .local import LocalFriction, constant_friction, local_friction
from .pattern import FootprintPattern, Grooves, read_footprint
from .results import Ranking, SlipMap, TreadResult
from .road import Road, as_road, contact_surface
from .simulate import DEFAULT_SLIPS, rank_surfaces, simulate, slip_map
from .tire import Footprint, Tire
from .wet import Water, WetState, bearing_lift, wet_state

__all__ = [
    "Tire", "Footprint", "Grooves", "FootprintPattern", "read_footprint", "Water", "WetState", "bearing_lift",
    "wet_state", "Road", "as_road", "contact_surface", "LocalFriction", "local_friction", "constant_friction",
    "simulate", "slip_map",
    "rank_surfaces", "TreadResult", "SlipMap", "Ranking", "DEFAULT_SLIPS",
]
