"""Generate the blind validation cases in ``tests/data/blind/`` (data the diagnosis has never been tuned on).

Usage (from the repository root)::

    python tests/data/blind/generate.py                  # every case
    python tests/data/blind/generate.py --only blind_two # one case

Why these data are not an inverse crime
---------------------------------------
The diagnosis evaluates the engine at its default resolution (``persson.GridSettings()``: 16 wavevector nodes
per decade, refined where its error estimate asks for it, 40 modulus nodes per decade; brush model with 401 nodes;
the cases were generated when the default was 24 nodes per decade). The truth here is computed

* with the engine at a far finer, converged resolution (:data:`TRUTH_GRID`: 6x the wavevector nodes, 3x the
  modulus table, a 2.5x finer temperature table; brush model with 1601 nodes), so the data do not
  carry the discretisation of the settings the diagnosis uses;
* checked, for the hysteresis and contact-area part, against :func:`persson.engine.reference.reference_friction`, an
  adaptive-quadrature implementation of the Persson integrals that shares no numerics with the engine (the
  largest relative difference is written to ``truth.json``);
* and, for ``blind_outside``, with a compound whose physics is not in the engine's candidate list at all: a
  Cole-Cole relaxation of the filler network (Cole & Cole, J. Chem. Phys. 9, 341 (1941)) added to the modulus,
  whose relaxation time follows an Arrhenius law, tau(T) = tau_ref exp(E_a / R (1/T - 1/T_ref)), not the
  compound's WLF law (filler-network relaxation in carbon-black filled rubber is thermally activated; e.g. Payne,
  J. Appl. Polym. Sci. 6, 57 (1962); Wang, Rubber Chem. Technol. 71, 520 (1998)). The case file declares only
  the unfilled master curve.

The surface (a self-affine PSD with H = 0.75, roll-off at 2 mm, hrms 0.1 mm) and the compound reference
temperature (25 C) are different from the shipped cases. Noise: Gaussian, ``numpy.random.default_rng(SEED +
index)``; absolute sigma 0.01 in mu unless stated (``mu_std`` written only where stated).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
SEED = 20260112
T_REF = 25.0

_SLIPS = (0.005, 0.01, 0.02, 0.04, 0.07, 0.1, 0.15, 0.2, 0.35, 0.6, 0.85)


@dataclass(frozen=True)
class Blind:
    """One blind case."""

    name: str
    description: str
    expect: str                          # what a correct diagnosis concludes (documentation for the tests)
    baseline_effects: dict               # name -> parameters as written in case.toml
    fit: tuple                           # [model] fit
    hidden: dict                         # name -> parameters of hidden built-in effects
    temperatures: tuple = ()
    pressures: tuple = ()
    speeds: tuple = ()                   # (min, max, n)
    slip_sweeps: tuple = ()              # ((V, T, p), ...) with the _SLIPS
    replicates: int = 1
    sigma: float = 0.01
    rel: float = 0.0                     # relative noise written as mu_std
    filler: dict = field(default_factory=dict)   # Cole-Cole filler process of the truth (blind_outside)
    contact_truth: dict = field(default_factory=dict)   # contact of the truth when it differs from the file
    contact_file: dict = field(default_factory=dict)    # contact written in case.toml when it differs from CONTACT


CASES = (
    Blind("blind_adhesion", "Hidden adhesion on a baseline of hysteresis only; no mu_std (noise from local "
          "differences).", "explained by adhesion",
          {}, (), {"adhesion": {"tau_f0": 1.2e6, "c": 0.15, "v_ref": 1.0e-3}},
          temperatures=(0.0, 15.0, 30.0, 45.0), pressures=(0.2e6, 0.4e6), speeds=(1e-4, 1.0, 9),
          slip_sweeps=((1.0, 20.0, 0.3e6),)),
    Blind("blind_two", "Two hidden effects at once (flash temperature and adhesion) on a baseline of hysteresis "
          "only.", "improve adds flash_temperature and adhesion, nothing else",
          {}, (), {"flash_temperature": {"macro_scale_ratio": 3.0},
                   "adhesion": {"tau_f0": 1.5e6, "c": 0.1, "v_ref": 3.0e-3}},
          temperatures=(0.0, 20.0, 40.0), pressures=(0.2e6, 0.5e6), speeds=(1e-3, 3.0, 10),
          slip_sweeps=((1.0, 20.0, 0.3e6), (3.0, 20.0, 0.3e6))),
    Blind("blind_null", "Nothing hidden: hysteresis + adhesion with tau_f0 fitted (given 0.7 MPa, true 1 MPa); "
          "every sliding condition measured three times (noise from replicates).", "nothing_missing",
          {"adhesion": {"tau_f0": 0.7e6, "c": 0.1, "v_ref": 1.0e-2}}, ("adhesion.tau_f0",),
          {"adhesion": {"tau_f0": 1.0e6, "c": 0.1, "v_ref": 1.0e-2}},
          temperatures=(0.0, 20.0, 40.0), pressures=(0.2e6, 0.5e6), speeds=(1e-3, 3.0, 7), replicates=3),
    Blind("blind_outside", "Missing physics outside the candidate list: an Arrhenius-shifted Cole-Cole filler "
          "process in the modulus (the case declares the unfilled master curve).", "unexplained or partly_explained",
          {}, (), {},
          temperatures=(-10.0, 10.0, 30.0, 50.0), pressures=(0.2e6, 0.4e6), speeds=(1e-4, 1.0, 9),
          slip_sweeps=((1.0, 20.0, 0.3e6),),
          filler={"delta_E": 8.0e6, "f_ref_Hz": 1.0e3, "alpha": 0.4, "E_a": 60.0e3}),
    Blind("blind_noise_level", "A hidden effect at the noise level: a weak strain softening whose rms effect "
          "on mu is about the noise.", "nothing_missing or explained by strain_softening",
          {"adhesion": {"tau_f0": 1.0e6, "c": 0.1, "v_ref": 1.0e-2}}, ("adhesion.tau_f0",),
          {"adhesion": {"tau_f0": 1.0e6, "c": 0.1, "v_ref": 1.0e-2},
           "strain_softening": {"storage_factor": 0.97, "loss_factor": 0.985}},
          temperatures=(0.0, 20.0, 40.0), pressures=(0.2e6, 0.5e6), speeds=(1e-3, 3.0, 9),
          slip_sweeps=((1.0, 20.0, 0.3e6),)),
    Blind("blind_slip", "Slip sweeps only (3 rolling speeds x 2 temperatures), hidden flash temperature, "
          "relative noise 1.5 % given as mu_std.", "explained by flash_temperature",
          {}, (), {"flash_temperature": {"macro_scale_ratio": 2.5}},
          slip_sweeps=((0.3, 10.0, 0.3e6), (1.0, 10.0, 0.3e6), (3.0, 10.0, 0.3e6),
                       (0.3, 30.0, 0.3e6), (1.0, 30.0, 0.3e6), (3.0, 30.0, 0.3e6)), rel=0.015),
    Blind("blind_slip_contact", "Slip sweeps only, nothing hidden, but the contact stiffness in the case file "
          "(5e9 Pa/m) is wrong: the truth has 2e9 Pa/m; [model] fit = [\"contact.stiffness\"].",
          "nothing_missing, contact.stiffness recovered within its uncertainty",
          {"adhesion": {"tau_f0": 1.0e6, "c": 0.1, "v_ref": 1.0e-2}}, ("contact.stiffness",),
          {"adhesion": {"tau_f0": 1.0e6, "c": 0.1, "v_ref": 1.0e-2}},
          slip_sweeps=((0.5, 20.0, 0.3e6), (2.0, 20.0, 0.3e6), (0.5, 35.0, 0.3e6)), sigma=0.008,
          contact_truth={"stiffness_Pa_per_m": 2.0e9}, contact_file={"stiffness_Pa_per_m": 5.0e9}),
)

CONTACT = {"length_m": 0.025, "width_m": 0.01, "stiffness_Pa_per_m": 2.5e9, "pressure_distribution": "parabolic"}


def truth_grid():
    """The converged resolution of the truth (see the module docstring)."""
    import persson

    return persson.GridSettings(q_per_decade=96, n_phi=64, omega_per_decade=120, temperature_step=0.1)


# ==========================================================================================================
@dataclass(frozen=True, eq=False)
class FillerNetwork:
    r"""A compound with an extra Cole-Cole relaxation of its filler network, Arrhenius-activated.

    .. math:: E(\omega, T) = E_0(\omega, T) + \Delta E \frac{(i\omega\tau)^\alpha}{1 + (i\omega\tau)^\alpha},
        \qquad \tau(T) = \frac{1}{2\pi f_{ref}} \exp\left[\frac{E_a}{R}\left(\frac1{T} - \frac1{T_{ref}}\right)\right]

    (Cole & Cole 1941; the storage and loss parts are Kramers-Kronig consistent). It has no ``log10_aT``: the engine
    evaluates it at every temperature directly, so its temperature dependence is not forced onto the WLF law.
    """

    base: object
    delta_E: float
    f_ref_Hz: float
    alpha: float
    E_a: float

    @property
    def thermal(self):
        return self.base.thermal

    def E(self, omega, T):
        omega = np.asarray(omega, dtype=float)
        T = np.asarray(T, dtype=float)
        tau = (np.exp(self.E_a / 8.314462618 * (1.0 / (T + 273.15) - 1.0 / (T_REF + 273.15)))
               / (2 * math.pi * self.f_ref_Hz))
        x = (1j * omega * tau) ** self.alpha
        return self.base.E(omega, T) + self.delta_E * x / (1.0 + x)


def _surface():
    import surfaces

    s = surfaces.SelfAffine(hurst=0.75, q0=2 * math.pi / 2e-3, q1=1.0e6, hrms=0.1e-3, qL=2 * math.pi / 20e-3)
    psd = s.tabulate(n_per_decade=16)
    return surfaces.PSD(psd.q, psd.C_values, source="blind test surface: self-affine H = 0.75, roll-off 2 mm, "
                        "hrms 0.1 mm", qL=psd.qL, q_rolloff=psd.q_rolloff, hurst=psd.hurst)


def _write_master_curve(path: Path):
    import materials
    from persson.io import write_csv

    tread = materials.example_tread()
    f = np.logspace(-8, 14, 8 * 22 + 1)
    E = tread.E(2 * np.pi * f, 20.0)
    write_csv(path, {"f_Hz": f, "E_storage_Pa": E.real, "E_loss_Pa": E.imag},
              comments=(f"master curve at T_ref = {T_REF:g} C: the 20 C curve of materials.example_tread() "
                        "declared at 25 C (a compound with its glass transition 5 K higher); synthetic",
                        "generated by tests/data/blind/generate.py"))


def _toml(v) -> str:
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml(x) for x in v) + "]"
    return repr(float(v)) if isinstance(v, float) else str(v)


def _case_toml(c: Blind) -> str:
    lines = [f"name = {json.dumps(c.name)}", f"# {c.description}",
             "# blind test case: generated by tests/data/blind/generate.py (truth on a converged grid)", "",
             "[surface]", 'psd = "surface_psd.csv"', "", "[material]", 'master_curve = "master_curve.csv"',
             f"wlf = {{ C1 = 8.86, C2 = 101.6, T_ref_C = {T_REF!r} }}", "poisson = 0.5",
             "thermal = { density = 1150.0, specific_heat = 1800.0, conductivity = 0.25 }", "", "[contact]"]
    lines += [f"{k} = {_toml(v)}" for k, v in dict(CONTACT, **c.contact_file).items()]
    lines += ["", "[model]", "gamma = 0.5", f"effects = {_toml(list(c.baseline_effects))}"]
    if c.fit:
        lines.append(f"fit = {_toml(list(c.fit))}")
    for eff, params in c.baseline_effects.items():
        lines += ["", f"[model.{eff}]"] + [f"{k} = {_toml(float(v))}" for k, v in params.items()]
    lines += ["", "[measurements]", 'file = "measurements.csv"', ""]
    return "\n".join(lines)


def _conditions(c: Blind):
    rows = []
    if c.speeds:
        lo, hi, n = c.speeds
        for T in c.temperatures:
            for p in c.pressures:
                for v in np.geomspace(lo, hi, n):
                    for _ in range(c.replicates):
                        rows.append((1.0, float(f"{v:.4g}"), T, p, f"sliding {T:g}C {p / 1e6:g}MPa"))
    for V, T, p in c.slip_sweeps:
        for s in _SLIPS:
            rows.append((s, V, T, p, f"slip sweep V={V:g}m/s {T:g}C {p / 1e6:g}MPa"))
    return rows


def _truth_model(spec, c: Blind):
    from persson import effects as fx

    model = spec.model.replace(grid=truth_grid(), effects=())
    if c.filler:
        model = model.replace(material=FillerNetwork(spec.model.material, **c.filler))
    for name, params in c.hidden.items():
        model = model.with_effect(fx.get(name, **params))
    return model


def _reference_check(model, rows) -> float | None:
    """Largest relative difference between the truth's hysteresis and the independent quadrature (None when the
    case has no sliding row to check)."""
    try:
        from persson.engine.reference import reference_friction
    except ImportError:
        return None
    base = model.replace(effects=())
    worst = None
    for slip, V, T, p, _ in rows[len(rows) // 3: len(rows) // 3 + 1]:   # one sliding row: seconds of quadrature
        if slip < 1:
            continue
        ref = reference_friction(base.surface, base.material, V, temperature=T, pressure=p, gamma=base.gamma,
                                 rtol=1e-6)
        mu_ref = float(np.atleast_1d(ref.mu if hasattr(ref, "mu") else ref[0])[0])
        mu_eng = float(base.friction(V, temperature=T, pressure=p).mu)
        worst = max(worst or 0.0, abs(mu_eng - mu_ref) / abs(mu_ref))
    return worst


def generate(c: Blind, index: int, out: Path = HERE) -> Path:
    from persson.case import read_case
    from persson.slip import Contact

    from validation import Measurements, predict

    folder = out / c.name
    folder.mkdir(parents=True, exist_ok=True)
    _surface().to_csv(folder / "surface_psd.csv")
    _write_master_curve(folder / "master_curve.csv")
    (folder / "case.toml").write_text(_case_toml(c), encoding="utf-8")
    rows = _conditions(c)
    slip, V, T, p, series = (list(x) for x in zip(*rows))
    skeleton = Measurements.from_arrays(slip=slip, speed=V, temperature=T, pressure=p, mu=np.full(len(rows), 0.5),
                                        series=series)
    skeleton.to_csv(folder / "measurements.csv", comments=("placeholder",))
    spec = read_case(folder / "case.toml")
    truth = _truth_model(spec, c)
    ckw = dict(CONTACT, **c.contact_truth)
    contact = Contact(ckw["length_m"], ckw["width_m"], ckw["stiffness_Pa_per_m"], ckw["pressure_distribution"],
                      n_points=1601)
    mu_true = predict(truth, skeleton, contact).mu
    mu_file = predict(spec.model, skeleton, spec.contact_model()).mu
    rng = np.random.default_rng(SEED + index)
    if c.rel > 0:
        sd = c.rel * mu_true
        mu = mu_true + rng.normal(0.0, 1.0, mu_true.size) * sd
        std = np.round(sd, 6)
        noise = {"kind": "relative", "rel": c.rel, "rms": float(np.sqrt(np.mean(sd ** 2)))}
    else:
        mu = mu_true + rng.normal(0.0, c.sigma, mu_true.size)
        std = None
        noise = {"kind": "absolute", "sigma": c.sigma, "rms": c.sigma}
    meas = Measurements.from_arrays(slip=slip, speed=V, temperature=T, pressure=p, mu=np.round(mu, 6), mu_std=std,
                                    series=series)
    meas.to_csv(folder / "measurements.csv", comments=(
        f"blind test case {c.name!r}: generated by tests/data/blind/generate.py (seed {SEED + index})",
        "speed_m_s is the rolling reference speed V; sliding speed = slip * V; slip = 1 is pure sliding"))
    info = {"name": c.name, "description": c.description, "expect": c.expect, "hidden": c.hidden,
            "filler": c.filler, "contact_truth": ckw, "noise": noise, "seed": SEED + index, "rows": meas.n,
            "truth_grid": {k: getattr(truth_grid(), k) for k in ("q_per_decade", "n_phi", "omega_per_decade",
                                                                 "temperature_step")},
            "rmse_truth_vs_case_model": float(np.sqrt(np.mean((mu_true - mu_file) ** 2))),
            "rmse_noise_realised": float(np.sqrt(np.mean((mu - mu_true) ** 2))),
            "reference_quadrature_max_rel_diff": _reference_check(truth, rows)}
    (folder / "truth.json").write_text(json.dumps(info, indent=2) + "\n", encoding="utf-8")
    for f in folder.iterdir():
        if f.is_file():
            f.chmod(0o644)
    print(f"{c.name}: {meas.n} rows; rms(truth - case model) {info['rmse_truth_vs_case_model']:.4f}; noise "
          f"{noise['rms']:.4f}; reference check {info['reference_quadrature_max_rel_diff']}")
    return folder / "case.toml"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", nargs="*", default=None)
    ap.add_argument("--out", default=str(HERE))
    args = ap.parse_args(argv)
    for i, c in enumerate(CASES):
        if args.only and c.name not in args.only:
            continue
        generate(c, i, Path(args.out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
