"""Friction-trailer raw channels -> mu-slip rows along the road -> peak and locked mu per position.

A road-friction trailer with three measuring tires braked at fixed slips records, at some 100 Hz, the forces of
two load cells per tire, the wheel speeds and the vehicle speed (Study on the influence of environmental
conditions on road friction characteristics, Lubricants 11(7), 277 (2023)). This package reduces such a record::

    from validation import rigs
    rig = rigs.load_rig("case.toml")                    # [[rig.tires]] tables, or a dict {"tires": [...]}
    raw = rigs.read_trailer("run.csv", rig)             # channels checked (names the line and column)
    rows = rigs.reduce(raw, rig, align=True)            # position_m, tire, slip, speed_m_s, mu
    profile = rigs.peak_lock_along_road(rows, step_m=1.0)   # peak_mu, locked_mu (+ std) per position
    meas = rows.to_measurements(temperature=20.0, pressure=2.0e5)   # for validation.compare / diagnose

* :mod:`.rig` - the rig's geometry and its checks;
* :mod:`.channels` - the raw file format and reader;
* :mod:`.balance` - braking force and normal load (Eqs. 8-9), the force-balance check of bad channels;
* :mod:`.align` - zero offsets, mu and slip per sample, running position, alignment of the tires' offsets;
* :mod:`.peaks` - three-point Magic Formula per position, peak and locked mu with uncertainties, dry vs wet.
"""

from .align import TrailerRows, reduce, running_position
from .balance import BalanceCheck, ChannelFlag, braking_force, check_balance, normal_load
from .channels import TrailerRun, read_trailer
from .peaks import PavementReduction, RoadProfile, peak_lock_along_road, peak_reduction_by_pavement
from .rig import Rig, TireMount, load_rig, rig_from_dict

__all__ = [
    "read_trailer", "reduce", "peak_lock_along_road", "peak_reduction_by_pavement", "check_balance",
    "load_rig", "rig_from_dict", "running_position", "braking_force", "normal_load",
    "Rig", "TireMount", "TrailerRun", "TrailerRows", "RoadProfile", "PavementReduction", "BalanceCheck",
    "ChannelFlag",
]
