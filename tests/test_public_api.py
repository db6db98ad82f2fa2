"""The documented public API, called exactly as outside scripts call it."""

import json

import numpy as np

import materials
import persson
import surfaces
import validation


def test_design_md_pipeline(tmp_path):
    s = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e7, hrms=20e-6)
    assert s.C(1e4) > 0 and s.hrms() > 0 and s.rms_slope() > 0 and s.with_cutoff(q1=1e6).q1 == 1e6

    rng = np.random.default_rng(1)
    x = np.arange(4096) * 10e-6
    z = np.cumsum(rng.normal(size=x.size)) * 1e-6
    (tmp_path / "scan.csv").write_text("x_m,z_m\n" + "\n".join(f"{float(a)!r},{float(b)!r}" for a, b in zip(x, z)))
    iso = surfaces.read_profiles(tmp_path / "scan.csv").psd().to_isotropic()
    assert isinstance(iso, surfaces.PSD) and iso.hrms() > 0

    m = materials.ConstantModulus(E_storage=5e6, E_loss=2e6)
    assert np.iscomplexobj(m.E(np.array([1.0, -1.0]), 20.0))
    tread = materials.example_tread()
    f = np.geomspace(0.1, 100, 8)
    rows = ["T_C,f_Hz,E_storage_Pa,E_loss_Pa"]
    for T in (-20.0, 0.0, 20.0, 40.0):
        E = tread.E(2 * np.pi * f, T)
        rows += [f"{T},{float(ff)!r},{float(e.real)!r},{float(e.imag)!r}" for ff, e in zip(f, E)]
    (tmp_path / "dma.csv").write_text("\n".join(rows) + "\n")
    mc = materials.master_curve(materials.read_dma(tmp_path / "dma.csv"), T_ref=20.0)
    assert np.iscomplexobj(mc.E(np.array([1.0, 10.0]), 30.0))

    model = persson.Model(s, mc, nu=0.5, gamma=0.5, effects=[persson.effects.FlashTemperature()])
    r = model.friction(np.array([1e-3, 1.0]), temperature=20.0, pressure=0.3e6)
    for name in ("mu", "mu_hysteresis", "mu_adhesion", "contact_area", "mean_separation", "penetration_depth"):
        assert np.shape(getattr(r, name)) == (2,) and np.all(np.isfinite(getattr(r, name)))
    for name in ("area_q", "temperature_q"):
        assert getattr(r, name).shape == (2, r.q.size)


def test_design_md_validation_calls(tmp_path):
    case = validation.load_case(validation.case_path("hidden_adhesion"))
    cmp = validation.compare(case.model, case.measurements)
    dx = validation.diagnose(case.model, case.measurements, candidates=["adhesion", "strain_softening"])
    out = validation.write_report([cmp, dx], tmp_path / "report.html")
    assert (tmp_path / "report.html").is_file() and out is not None
    js = json.loads(dx.to_json())
    assert {"baseline", "candidates"} <= set(js)  # the contract's keys; more may be added
    assert {"rmse", "effects"} <= set(js["baseline"])
    for c in js["candidates"]:
        assert {"effect", "rmse", "delta_bic", "significant", "parameters"} <= set(c)
    assert js["candidates"][0]["effect"] == "adhesion"
