"""Persson's theory for tread rubber on a road: the engine against the theory's own limit and against what the
published work states, and what the low friction of the realistic road case comes from.

Run ``python benchmarks/published_friction.py [--quick]``. Three tables (markdown), as in docs/slip.md section 6:

1. **The theory's small-contact limit.** For a modulus of constant phase (E'' / E' = tan delta at every
   frequency) Persson's equations reduce to one integral over the rms slope (Persson, J. Chem. Phys. 115, 3840
   (2001) with S = gamma + (1 - gamma) P^2, Yang & Persson 2008):

       mu = (4 E''* sigma0 / (pi |E*|^2)) int_0^x1 x erf(1/x) S(erf(1/x)) dx,   x1 = |E*| xi(q1) / (sqrt(2) sigma0),

   which tends to (4 sqrt(2) / pi^(3/2)) gamma sin(delta) xi(q1) = 1.016 gamma sin(delta) xi(q1) when the real
   contact is small. The engine (``persson.Model`` with ``materials.ConstantModulus``) on the case's road against
   that integral (scipy quad, no engine code) and the limit.
2. **Published statements, ours against theirs**, on the case's road and compound with the flash temperature
   (``persson.slip.example_road_case().model`` without the patch heating): where the flash temperature makes mu
   fall with speed (Persson, J. Phys.: Condens. Matter 18, 7789 (2006)), from which speed frictional heating
   matters (Fortunato et al., J. Phys.: Condens. Matter 27, 175008 (2015)), the real contact area at ABS sliding
   speeds (Sensitivity Analysis of Tire-Road Friction Coefficient to Pavement Texture Parameters Using a
   Physics-Based Contact Model, Road Profile Users' Group meeting (2015)), the share of the contact-area
   term
   at low speeds (Lorenz, Oh, Nam, Jeon & Persson, J. Chem. Phys. 142, 194701 (2015)).
3. **Sensitivity of the realistic case**: the sliding mu at 0.3, 1 and 3 m/s (20 C, flash temperature) and the
   peak of mu(s) (with the tire's carcass, patch heating and flash, 0, 20 and 40 C, 20 and 100 km/h) when one input
   changes: gamma, the contact-area correction, the short-distance cut-off q1, the road's roll-off, roughness and
   Hurst exponent, the adhesion shear stress, the
   nominal pressure, strain softening, the compound, the size of the flash hot spots, and combinations.
4. **Friction against the road temperature** at 1 m/s (flash temperature), hysteresis and total, for the case and
   for one combination that reaches a tire's level: where the friction is largest decides whether the patch
   heating of a braked tire lowers or raises it.

The engine runs on a coarse grid (12 nodes per decade of q, 20 per decade of frequency, tolerance 1e-2; the
numbers agree with the default grid within 1e-4 in mu for the case). About 1-2 minutes on a busy 2-core machine
(``--quick``: tables 1 and 2 only, under a minute).
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
import warnings

import numpy as np
from scipy import integrate
from scipy.special import erf

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

import materials  # noqa: E402
import persson  # noqa: E402
import surfaces  # noqa: E402
from persson import slip as ps  # noqa: E402
from persson.effects import Adhesion, FlashTemperature, StrainSoftening  # noqa: E402

GRID = persson.GridSettings(q_per_decade=12, omega_per_decade=20, tolerance=1e-2, temperature_step=1.0)
HEATING = ps.PatchHeating(points_per_decade=2, n_pressure=4, temperature_points_per_decade=2)
SIGMA0 = 0.3e6
SLIDING = np.array([0.3, 1.0, 3.0])
SLIPS = np.concatenate([np.geomspace(0.002, 0.3, 16), [0.5, 0.75, 1.0]])
LIMIT_FACTOR = 4.0 * math.sqrt(2.0) / math.pi ** 1.5


# ---------------------------------------------------------------------------------------------- 1. the limit

def constant_phase_mu(E_storage: float, tan_delta: float, xi1: float, sigma0: float, gamma: float,
                      nu: float = 0.5) -> float:
    """Persson's hysteresis friction for a frequency-independent modulus, by one quadrature over the rms slope."""
    Es = abs(complex(E_storage, E_storage * tan_delta)) / (1.0 - nu * nu)
    El = E_storage * tan_delta / (1.0 - nu * nu)
    x1 = Es * xi1 / (math.sqrt(2.0) * sigma0)

    def integrand(x):
        P = erf(1.0 / x) if x > 0 else 1.0
        return x * P * (gamma + (1.0 - gamma) * P * P)

    value, _ = integrate.quad(integrand, 0.0, x1, limit=400, epsabs=0.0, epsrel=1e-11)
    return 4.0 * El * sigma0 / (math.pi * Es * Es) * value


def small_contact_table(road):
    xi1 = road.rms_slope()
    print(f"### 1. Small-contact limit on the case's road (rms slope {xi1:.3f}), sigma0 = {SIGMA0 / 1e6:g} MPa, "
          "E' = 10 MPa\n")
    print("| tan delta | gamma | engine | one-integral quadrature | 1.016 gamma sin(delta) xi(q1) |")
    print("|---|---|---|---|---|")
    for tan in (0.3, 0.56, 1.0):
        for gamma in (0.5, 1.0):
            m = materials.ConstantModulus(E_storage=10e6, E_loss=10e6 * tan)
            r = persson.Model(road, m, gamma=gamma).friction(1.0, temperature=20.0, pressure=SIGMA0)
            ref = constant_phase_mu(10e6, tan, xi1, SIGMA0, gamma)
            lim = LIMIT_FACTOR * gamma * math.sin(math.atan(tan)) * xi1
            print(f"| {tan:g} | {gamma:g} | {float(r.mu):.4f} | {ref:.4f} | {lim:.4f} |")
    print()


# ---------------------------------------------------------------------------------------------- 2. statements

def statements_table(case):
    base = case.model.without("patch_heating").replace(grid=GRID)
    plain = base.without("flash_temperature")
    v = np.geomspace(1e-4, 30.0, 25)
    rows = []
    for T0 in (0.0, 20.0, 40.0):
        hot = base.friction(v, temperature=T0, pressure=SIGMA0)
        cold = plain.friction(v, temperature=T0, pressure=SIGMA0)
        rows.append((T0, hot, cold))
    print("### 2. Published statements against the engine (case road and compound, flash temperature, adhesion "
          "2 MPa)\n")
    print("| source | states | ours (T0 = 0 / 20 / 40 C) |")
    print("|---|---|---|")
    vmax = [float(v[np.argmax(h.mu)]) for _, h, _ in rows]
    drop = [float(h.mu[v <= 3.0][-1] / h.mu.max()) for _, h, _ in rows]
    print("| Persson, J. Phys.: Condens. Matter 18, 7789 (2006), abstract | with the flash temperature mu falls with "
          "speed above about 0.01 m/s in a typical case | mu largest at "
          f"{' / '.join(f'{x:.2g}' for x in vmax)} m/s; at 3 m/s {' / '.join(f'{x:.2f}' for x in drop)} of it |")
    cells = []
    for _, h, c in rows:
        rel = (h.mu - c.mu) / c.mu
        cells.append(", ".join(f"{rel[np.argmin(abs(v - x))] * 100:+.0f} %" for x in (1e-3, 1e-2, 1.0)))
    print("| Fortunato et al., J. Phys.: Condens. Matter 27, 175008 (2015), abstract | frictional heating matters "
          "for rubber on roads above 1 mm/s | change of mu by the flash at 1 mm/s, 1 cm/s, 1 m/s: "
          f"{' / '.join(cells)} |")
    area = [h.contact_area[(v >= 0.3) & (v <= 3.0)] for _, h, _ in rows]
    print("| Road Profile Users' Group meeting (2015), texture-sensitivity study | real contact area about 1 % at "
          "ABS sliding speeds for a real tread compound | A/A0 at 0.3-3 m/s: "
          f"{' / '.join(f'{a.min() * 100:.1f}-{a.max() * 100:.1f} %' for a in area)} |")
    share = [h.mu_adhesion[v <= 1e-2] / h.mu[v <= 1e-2] for _, h, _ in rows]
    print("| Lorenz, Oh, Nam, Jeon & Persson, J. Chem. Phys. 142, 194701 (2015), abstract | besides the "
          "viscoelastic deformations, shear in the area of real contact contributes importantly (low speeds) | "
          f"share of the adhesive term at 0.1 mm/s-1 cm/s: "
          f"{' / '.join(f'{s.min() * 100:.0f}-{s.max() * 100:.0f} %' for s in share)} |")
    lvl = [h.mu[(v >= 0.3) & (v <= 3.0)] for _, h, _ in rows]
    print("| (the level) | | mu at 0.3-3 m/s: "
          f"{' / '.join(f'{x.min():.2f}-{x.max():.2f}' for x in lvl)} |")
    print()


# ---------------------------------------------------------------------------------------------- 3. sensitivity

def _road(q1=1e6, hurst=0.8, rolloff=5e-3, hrms=0.2e-3):
    return surfaces.SelfAffine(hurst=hurst, q0=2 * math.pi / rolloff, q1=q1, hrms=hrms, qL=2 * math.pi / 0.1)


def scenarios(case):
    """(label, friction model without patch heating, compound) per scenario."""
    tire = materials.example_tire_tread()

    def model(road=None, material=None, effects=None, **options):
        effects = (Adhesion(),) if effects is None else effects
        return persson.Model(road or _road(), material or tire, effects=(FlashTemperature(),) + tuple(effects),
                             grid=GRID, **options)

    soft = StrainSoftening()
    return [
        ("the case (tread + carcass)", model(), None),
        ("gamma = 1 (S = 1, the theory before 2008)", model(gamma=1.0), None),
        ("area correction yang-persson", model(correction="yang-persson"), None),
        ("q1 = 3e5 rad/m (rms slope 1.06)", model(road=_road(3e5)), None),
        ("q1 = 3e6 rad/m (rms slope 1.74)", model(road=_road(3e6)), None),
        ("q1 = 1e7 rad/m (rms slope 2.23)", model(road=_road(1e7)), None),
        ("road: roll-off at 1 cm, h_rms 0.4 mm (rms slope 1.60)", model(road=_road(rolloff=1e-2, hrms=0.4e-3)), None),
        ("road: H = 0.7 (rms slope 2.17)", model(road=_road(hurst=0.7)), None),
        ("no adhesion", model(effects=()), None),
        ("adhesion tau_f0 = 5 MPa", model(effects=(Adhesion(tau_f0=5e6),)), None),
        ("adhesion tau_f0 = 10 MPa", model(effects=(Adhesion(tau_f0=10e6),)), None),
        ("strain softening f = 0.5, g = 0.7", model(effects=(Adhesion(), soft)), None),
        ("strain softening f = 0.3, g = 0.5", model(effects=(Adhesion(), StrainSoftening(storage_factor=0.3,
                                                                                         loss_factor=0.5))), None),
        ("flash hot spots half as large (macro_scale_ratio 4)",
         persson.Model(_road(), tire, effects=(FlashTemperature(macro_scale_ratio=4.0), Adhesion()), grid=GRID),
         None),
        ("compound example_tread (T_g 8 K lower, softer)", model(material=materials.example_tread()),
         materials.example_tread()),
        ("softening 0.5/0.7 + tau_f0 = 5 MPa", model(effects=(Adhesion(tau_f0=5e6), soft)), None),
        ("softening 0.5/0.7 + tau_f0 = 10 MPa", model(effects=(Adhesion(tau_f0=10e6), soft)), None),
        ("gamma = 1 + softening 0.5/0.7 + tau_f0 = 5 MPa", model(effects=(Adhesion(tau_f0=5e6), soft), gamma=1.0),
         None),
    ]


def peaks(case, model, compound, temperatures=(0.0, 20.0, 40.0), kmh=(20.0, 100.0)):
    """{(T0, V km/h): (peak, slip at peak, locked)} of the brush with the case's tread and carcass."""
    compound = compound or case.model.material
    road_model = ps.with_road_heating(model, patch_heating=HEATING)
    k_c = case.carcass_stiffness
    out = {}
    for T0 in temperatures:
        for V in kmh:
            c = ps.Contact.from_tread(case.length, case.width, case.tread, compound, speed=V / 3.6, temperature=T0,
                                      n_points=101, carcass_stiffness=k_c)
            r = ps.mu_slip(road_model, SLIPS, V / 3.6, temperature=T0, pressure=case.pressure, contact=c)
            pk, at = r.peak()
            out[T0, V] = (float(pk), float(at), float(r.mu[-1]))
    return out


def sensitivity_table(case):
    print("### 3. Sensitivity of the realistic case\n")
    print("Sliding mu at 0.3 / 1 / 3 m/s (20 C, 0.3 MPa, flash temperature), A/A0 at 1 m/s; peak of mu(s) at "
          "0 / 20 / 40 C and 20 km/h (its slip), at 20 C and 100 km/h, and the locked/peak ratio at 20 C, "
          "20 km/h (tread + carcass, patch heating and flash).\n")
    print("| input | mu sliding 0.3 / 1 / 3 m/s | mu hysteresis at 1 m/s | A/A0 at 1 m/s | peak 0 / 20 / 40 C, "
          "20 km/h (slip) | peak 20 C, 100 km/h | locked/peak 20 C, 20 km/h |")
    print("|---|---|---|---|---|---|---|")
    for label, model, compound in scenarios(case):
        r = model.friction(SLIDING, temperature=20.0, pressure=SIGMA0)
        pk = peaks(case, model, compound)
        cells = " / ".join(f"{pk[T, 20.0][0]:.2f} ({pk[T, 20.0][1] * 100:.1f} %)" for T in (0.0, 20.0, 40.0))
        fast = pk[20.0, 100.0]
        print(f"| {label} | {' / '.join(f'{x:.2f}' for x in r.mu)} | {float(r.mu_hysteresis[1]):.2f} | "
              f"{float(r.contact_area[1]) * 100:.1f} % | {cells} | {fast[0]:.2f} ({fast[1] * 100:.1f} %) | "
              f"{pk[20.0, 20.0][2] / pk[20.0, 20.0][0]:.2f} |", flush=True)
    for p in (0.2e6, 0.43e6, 0.6e6):
        r = scenarios(case)[0][1].friction(SLIDING, temperature=20.0, pressure=p)
        print(f"| nominal pressure {p / 1e6:g} MPa (sliding only) | {' / '.join(f'{x:.2f}' for x in r.mu)} | "
              f"{float(r.mu_hysteresis[1]):.2f} | {float(r.contact_area[1]) * 100:.1f} % | | | |")
    print()


def temperature_table(case):
    temperatures = (0.0, 10.0, 20.0, 40.0, 60.0, 80.0, 100.0)
    models = [(label, model) for label, model, _ in scenarios(case)
              if label in ("the case (tread + carcass)", "softening 0.5/0.7 + tau_f0 = 10 MPa")]
    print("### 4. Sliding mu at 1 m/s against the road temperature (flash temperature, 0.3 MPa)\n")
    print("| model | " + " | ".join(f"{T:g} C" for T in temperatures) + " |")
    print("|---|" + "---|" * len(temperatures))
    for label, model in models:
        r = [model.friction(1.0, temperature=T, pressure=SIGMA0) for T in temperatures]
        print(f"| {label}: mu | " + " | ".join(f"{float(x.mu):.2f}" for x in r) + " |")
        print(f"| {label}: mu hysteresis | " + " | ".join(f"{float(x.mu_hysteresis):.2f}" for x in r) + " |")
    print()


def main(quick: bool = False):
    t0 = time.perf_counter()
    case = ps.example_road_case(grid=GRID, patch_heating=HEATING)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", persson.AccuracyWarning)      # the coarse grid
        small_contact_table(case.model.surface)
        statements_table(case)
        if not quick:
            sensitivity_table(case)
            temperature_table(case)
    print(f"({time.perf_counter() - t0:.0f} s)")


if __name__ == "__main__":
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true", help="the limit and the published statements only")
    main(p.parse_args().quick)
