"""Generate the validation cases shipped in ``validation/cases/`` (synthetic, seeded, documented).

Usage::

    python -m validation.generate_cases                 # rewrite every case in validation/cases
    python -m validation.generate_cases --only null     # one case
    python -m validation.generate_cases --out /tmp/c    # elsewhere

For every case the script

1. writes the surface PSD table (``surface_psd.csv``, :meth:`surfaces.PSD.to_csv`), the master-curve table of the
   compound at its reference temperature (``master_curve.csv``: ``f_Hz, E_storage_Pa, E_loss_Pa`` of
   :func:`materials.example_tread`, 8 points per decade) and ``case.toml``;
2. loads the case back with :func:`persson.case.read_case` -- so the truth is computed with exactly the model
   a user of the case gets (the master curve table is read by :func:`materials.read_master_curve`);
3. computes the truth = the case's baseline + the hidden effect (none for ``null``) on the case's measurement
   conditions with :func:`validation.predict` (sliding rows, brush-model slip rows, wet rows), on a converged
   grid (128 wavevector and 160 modulus nodes per decade, ``CONVERGED_GRID``), not the default grid the
   diagnosis uses;
4. adds Gaussian noise from ``numpy.random.default_rng(SEED + index)`` -- absolute (``sigma`` in mu) or
   relative (``rel`` times the true mu, then written as the ``mu_std`` column) -- and writes
   ``measurements.csv``;
5. writes ``truth.json`` (hidden effect, its parameters, noise level, seed) for the tests and the README.

The data are synthetic: they test that the diagnosis finds an effect that is known to be there (and nothing
when nothing is), not that the physics describes real rubber.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

SEED = 20250607
CASES_DIR = Path(__file__).resolve().parent / "cases"


def _converged_grid():
    from persson import GridSettings

    return GridSettings(q_per_decade=128, omega_per_decade=160)


CONVERGED_GRID = _converged_grid()

__all__ = ["SEED", "CASES", "CaseDef", "generate", "main"]


@dataclass(frozen=True)
class CaseDef:
    """Definition of one synthetic case (see the module docstring)."""

    name: str
    description: str
    surface: str                      # "road", "road_qr" (table ends at the profilometer limit), "sandpaper"
    material_T_ref: float             # T_ref of the master-curve table (20: example_tread; 10: a softer compound)
    baseline_effects: tuple           # names, with parameters in baseline_params
    baseline_params: dict
    fit: tuple                        # [model] fit
    hidden: str | None
    hidden_params: dict
    temperatures: tuple
    pressures: tuple
    speeds: tuple                     # (min, max, n) of sliding speeds, log-spaced
    slip_sweeps: tuple = ()           # ((V, T, p, (slips...)), ...)
    wet: tuple = ()                   # ((T, p, (min, max, n)), ...) wet sliding rows
    sigma: float = 0.01               # absolute noise (when rel == 0)
    rel: float = 0.0                  # relative noise, written as mu_std
    contact: dict = field(default_factory=lambda: {"length_m": 0.02, "width_m": 0.01,
                                                   "stiffness_Pa_per_m": 3.0e9,
                                                   "pressure_distribution": "parabolic"})


_SLIPS = (0.005, 0.01, 0.02, 0.04, 0.07, 0.1, 0.2, 0.35, 0.6, 0.85)

CASES = (
    CaseDef(
        name="example",
        description=("DRFT-style example for `persson demo`: a tread on a road-like surface; sliding at 8 speeds, "
                     "3 temperatures, 2 pressures, slip sweeps at two rolling speeds, wet sliding rows. Baseline: "
                     "hysteresis + adhesion (tau_f0 fitted); hidden: flash temperature."),
        surface="road", material_T_ref=20.0, baseline_effects=("adhesion",),
        baseline_params={"adhesion": {"tau_f0": 1.0e6, "c": 0.1, "v_ref": 1.0e-2}}, fit=("adhesion.tau_f0",),
        hidden="flash_temperature", hidden_params={"macro_scale_ratio": 3.0},
        temperatures=(5.0, 20.0, 40.0), pressures=(0.2e6, 0.4e6), speeds=(1e-3, 2.0, 8),
        slip_sweeps=((0.5, 20.0, 0.3e6, _SLIPS), (2.0, 20.0, 0.3e6, _SLIPS)),
        wet=((20.0, 0.3e6, (1e-3, 2.0, 6)),), sigma=0.01),
    CaseDef(
        name="hidden_flash",
        description=("150 rows (the timing case): 4 temperatures x 3 pressures x 10 speeds of sliding plus 3 slip "
                     "sweeps; baseline hysteresis only; hidden: flash temperature."),
        surface="road", material_T_ref=20.0, baseline_effects=(), baseline_params={}, fit=(),
        hidden="flash_temperature", hidden_params={"macro_scale_ratio": 4.0},
        temperatures=(0.0, 15.0, 30.0, 45.0), pressures=(0.15e6, 0.3e6, 0.6e6), speeds=(1e-4, 3.0, 10),
        slip_sweeps=((0.3, 20.0, 0.3e6, _SLIPS), (1.0, 20.0, 0.3e6, _SLIPS), (3.0, 20.0, 0.3e6, _SLIPS)),
        sigma=0.01),
    CaseDef(
        name="hidden_adhesion",
        description=("Sandpaper-like surface, softer compound (T_ref 10 C), relative noise 2 % given as mu_std; "
                     "baseline hysteresis only; hidden: adhesion."),
        surface="sandpaper", material_T_ref=10.0, baseline_effects=(), baseline_params={}, fit=(),
        hidden="adhesion", hidden_params={"tau_f0": 1.5e6, "c": 0.12, "v_ref": 3.0e-4},
        temperatures=(0.0, 20.0, 40.0), pressures=(0.1e6, 0.3e6), speeds=(1e-4, 1.0, 9),
        slip_sweeps=((0.5, 20.0, 0.3e6, _SLIPS),), rel=0.02),
    CaseDef(
        name="hidden_microtexture",
        description=("Road PSD measured only down to the profilometer limit q_r = 1e5 rad/m (the table ends there); "
                     "baseline hysteresis only; hidden: microtexture (the self-affine tail continued to 2e6 rad/m)."),
        surface="road_qr", material_T_ref=20.0, baseline_effects=(), baseline_params={}, fit=(),
        hidden="microtexture", hidden_params={"q1": 2.0e6},
        temperatures=(0.0, 20.0, 40.0), pressures=(0.2e6, 0.5e6), speeds=(1e-3, 3.0, 9),
        slip_sweeps=((1.0, 20.0, 0.3e6, _SLIPS),), sigma=0.01),
    CaseDef(
        name="hidden_strain_softening",
        description=("Road surface, baseline hysteresis + adhesion (tau_f0 fitted); hidden: strain softening of the "
                     "compound (E' x 0.55, E'' x 0.75)."),
        surface="road", material_T_ref=20.0, baseline_effects=("adhesion",),
        baseline_params={"adhesion": {"tau_f0": 0.8e6, "c": 0.1, "v_ref": 1.0e-2}}, fit=("adhesion.tau_f0",),
        hidden="strain_softening", hidden_params={"storage_factor": 0.55, "loss_factor": 0.75},
        temperatures=(0.0, 20.0, 40.0), pressures=(0.2e6, 0.5e6), speeds=(1e-3, 3.0, 9),
        slip_sweeps=((1.0, 20.0, 0.3e6, _SLIPS),), sigma=0.01),
    CaseDef(
        name="null",
        description=("Nothing hidden: the data are the baseline (hysteresis + adhesion) plus noise; sliding, slip "
                     "and wet rows."),
        surface="road", material_T_ref=20.0, baseline_effects=("adhesion",),
        baseline_params={"adhesion": {"tau_f0": 1.0e6, "c": 0.1, "v_ref": 1.0e-2}}, fit=(),
        hidden=None, hidden_params={},
        temperatures=(0.0, 20.0, 40.0), pressures=(0.2e6, 0.5e6), speeds=(1e-3, 3.0, 9),
        slip_sweeps=((1.0, 20.0, 0.3e6, _SLIPS),), wet=((20.0, 0.3e6, (1e-3, 3.0, 6)),), sigma=0.01),
)


# ==========================================================================================================
def _surface(kind: str):
    import surfaces

    if kind in ("road", "road_qr"):
        road = surfaces.example_road()   # H = 0.8, q0 = 1.26e3, qL = 62.8 rad/m, hrms 0.35 mm (synthetic)
        q1 = 1.0e5 if kind == "road_qr" else 1.0e6
        psd = road.with_cutoff(q1=q1).tabulate(n_per_decade=16)
        if kind == "road_qr":
            # the table ends at the instrument's reliability limit
            return surfaces.PSD(psd.q, psd.C_values, q_r=float(psd.q[-1]),
                                source="synthetic road PSD (surfaces.example_road) measured down to q_r = 1e5 rad/m",
                                qL=psd.qL, q_rolloff=psd.q_rolloff, hurst=psd.hurst)
        return surfaces.PSD(psd.q, psd.C_values, source="synthetic road PSD (surfaces.example_road, q1 = 1e6 rad/m)",
                            qL=psd.qL, q_rolloff=psd.q_rolloff, hurst=psd.hurst)
    if kind == "sandpaper":
        sp = surfaces.SelfAffine(hurst=0.7, q0=2 * math.pi / 0.3e-3, q1=1.0e6, hrms=40e-6, qL=2 * math.pi / 5e-3)
        psd = sp.tabulate(n_per_decade=16)
        return surfaces.PSD(psd.q, psd.C_values,
                            source="synthetic sandpaper-like PSD (H = 0.7, roll-off 0.3 mm, hrms 40 um)",
                            qL=psd.qL, q_rolloff=psd.q_rolloff, hurst=psd.hurst)
    raise ValueError(kind)


def _write_master_curve(path: Path, T_ref: float):
    import materials
    from persson.io import write_csv

    tread = materials.example_tread()
    f = np.logspace(-8, 14, 8 * 22 + 1)
    E = tread.E(2 * np.pi * f, 20.0)   # the table of example_tread at 20 C, declared at T_ref below
    write_csv(path, {"f_Hz": f, "E_storage_Pa": E.real, "E_loss_Pa": E.imag}, overwrite=True,
              comments=(f"master curve at T_ref = {T_ref:g} C: materials.example_tread() (synthetic; its 20 C "
                        "curve)" + ("" if T_ref == 20.0 else f" declared at {T_ref:g} C, i.e. a compound with "
                                    f"its glass transition {20 - T_ref:g} K lower"),
                        "generated by validation/generate_cases.py"))


def _toml_value(v) -> str:
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, float):
        return repr(float(v))  # np.float64 is a float; its numpy-2 repr is not TOML
    return str(v)


def _case_toml(c: CaseDef) -> str:
    lines = [f"name = {json.dumps(c.name)}",
             f"# {c.description}",
             "# synthetic case: generated by validation/generate_cases.py (see validation/cases/README.md)",
             "", "[surface]", 'psd = "surface_psd.csv"', "",
             "[material]", 'master_curve = "master_curve.csv"',
             f"wlf = {{ C1 = 8.86, C2 = 101.6, T_ref_C = {c.material_T_ref!r} }}",
             "poisson = 0.5",
             "thermal = { density = 1150.0, specific_heat = 1800.0, conductivity = 0.25 }", "",
             "[contact]"]
    lines += [f"{k} = {_toml_value(v)}" for k, v in c.contact.items()]
    lines += ["", "[model]", "gamma = 0.5", f"effects = {_toml_value(list(c.baseline_effects))}"]
    if c.fit:
        lines.append(f"fit = {_toml_value(list(c.fit))}")
    for eff, params in c.baseline_params.items():
        lines += ["", f"[model.{eff}]"] + [f"{k} = {_toml_value(float(v))}" for k, v in params.items()]
    lines += ["", "[measurements]", 'file = "measurements.csv"', ""]
    return "\n".join(lines)


def _conditions(c: CaseDef):
    rows = []  # (slip, V, T, p, wet, series)
    lo, hi, n = c.speeds
    for T in c.temperatures:
        for p in c.pressures:
            for v in np.geomspace(lo, hi, n):
                rows.append((1.0, float(f"{v:.4g}"), T, p, 0, f"sliding {T:g}C {p / 1e6:g}MPa"))
    for V, T, p, slips in c.slip_sweeps:
        for s in slips:
            rows.append((s, V, T, p, 0, f"slip sweep V={V:g}m/s {T:g}C {p / 1e6:g}MPa"))
    for T, p, (lo_w, hi_w, n_w) in c.wet:
        for v in np.geomspace(lo_w, hi_w, n_w):
            rows.append((1.0, float(f"{v:.4g}"), T, p, 1, f"wet {T:g}C {p / 1e6:g}MPa"))
    return rows


def generate(case: CaseDef, index: int, out_dir: Path = CASES_DIR, verbose: bool = True) -> Path:
    """Write one case folder (see the module docstring); returns its case.toml."""
    from persson import effects as fx
    from persson.case import read_case

    from .measurements import Measurements
    from .predict import predict

    folder = Path(out_dir) / case.name
    folder.mkdir(parents=True, exist_ok=True)
    _surface(case.surface).to_csv(folder / "surface_psd.csv", overwrite=True)
    _write_master_curve(folder / "master_curve.csv", case.material_T_ref)
    (folder / "case.toml").write_text(_case_toml(case), encoding="utf-8")
    rows = _conditions(case)
    slip, V, T, p, wet, series = (list(x) for x in zip(*rows))
    skeleton = Measurements.from_arrays(slip=slip, speed=V, temperature=T, pressure=p, mu=np.full(len(rows), 0.5),
                                        wet=wet, series=series, source=str(folder / "measurements.csv"))
    skeleton.to_csv(folder / "measurements.csv", comments=("placeholder: being generated",), overwrite=True)
    spec = read_case(folder / "case.toml")
    # the truth is computed on a converged grid, far finer than the default the diagnosis uses, so that the
    # engine's own discretisation error cannot cancel out when the diagnosis is tested on these data
    model = spec.model.replace(grid=CONVERGED_GRID)
    truth = model if case.hidden is None else model.with_effect(fx.get(case.hidden, **case.hidden_params))
    mu_true = predict(truth, skeleton, spec.contact_model()).mu
    mu_base = predict(model, skeleton, spec.contact_model()).mu
    rng = np.random.default_rng(SEED + index)
    if case.rel > 0:
        sd = case.rel * mu_true
        mu = mu_true + rng.normal(0.0, 1.0, mu_true.size) * sd
        std = np.round(sd, 6)
        noise = {"kind": "relative", "rel": case.rel, "rms": float(np.sqrt(np.mean(sd ** 2)))}
    else:
        mu = mu_true + rng.normal(0.0, case.sigma, mu_true.size)
        std = None
        noise = {"kind": "absolute", "sigma": case.sigma, "rms": case.sigma}
    mu = np.maximum(mu, 0.0)
    meas = Measurements.from_arrays(slip=slip, speed=V, temperature=T, pressure=p, mu=mu, mu_std=std, wet=wet,
                                    series=series, source=str(folder / "measurements.csv"))
    meas.to_csv(folder / "measurements.csv", overwrite=True, comments=(
        f"synthetic DRFT-style measurements of case {case.name!r}: generated by validation/generate_cases.py "
        f"(seed {SEED + index}); see validation/cases/README.md",
        "speed_m_s is the rolling reference speed V; sliding speed = slip * V; slip = 1 is pure sliding"))
    info = {"name": case.name, "description": case.description, "hidden": case.hidden,
            "parameters": {k: float(v) for k, v in case.hidden_params.items()}, "noise": noise,
            "seed": SEED + index, "rows": meas.n,
            "grid": {"q_per_decade": CONVERGED_GRID.q_per_decade, "omega_per_decade": CONVERGED_GRID.omega_per_decade},
            "rmse_truth_vs_baseline": float(np.sqrt(np.mean((mu_true - mu_base) ** 2))),
            "rmse_noise_realised": float(np.sqrt(np.mean((mu - mu_true) ** 2)))}
    (folder / "truth.json").write_text(json.dumps(info, indent=2) + "\n", encoding="utf-8")
    for f in folder.iterdir():   # package data: readable by everyone (atomic writes create 0600 files)
        if f.is_file():
            f.chmod(0o644)
    if verbose:
        print(f"{case.name}: {meas.n} rows, truth = baseline + {case.hidden or 'nothing'}; rms(truth - baseline) "
              f"{info['rmse_truth_vs_baseline']:.4f}, noise rms {noise['rms']:.4f}; mu {mu.min():.3f}-{mu.max():.3f}"
              f" -> {folder}")
    return folder / "case.toml"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=str(CASES_DIR), help="folder for the case folders")
    ap.add_argument("--only", nargs="*", default=None, help="case names to (re)generate")
    args = ap.parse_args(argv)
    for i, c in enumerate(CASES):
        if args.only and c.name not in args.only:
            continue
        generate(c, i, Path(args.out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
