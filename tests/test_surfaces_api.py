"""Public API contract of :mod:`surfaces` (docs/conventions.md), citations and plots."""

import math

import matplotlib
import numpy as np
import pytest

import frictioncite
import surfaces
from surfaces import plots


def _scan_csv(tmp_path, seed=0, n=2048, name="scan.csv"):
    truth = surfaces.SelfAffine(hurst=0.8, q0=2e3, q1=5e5, hrms=50e-6, qL=2e2)
    ps = surfaces.synthesize_profiles(truth, n_profiles=2, n=n, seed=seed)
    x_mm = ps[0].x * 1e3
    z = np.stack([p.z * 1e6 for p in ps], axis=1)
    z[100:110, 0] = np.nan
    rows = "\n".join(f"{a:.6f},{b:.5f},{c:.5f}" for a, (b, c) in zip(x_mm, z))
    path = tmp_path / name
    path.write_text("# synthetic scan\nx_mm,z1_um,z2_um\n" + rows.replace("nan", "") + "\n")
    return path


def test_design_md_pipeline(tmp_path):
    """surfaces.read_profiles("scan.csv").psd().to_isotropic() -> surfaces.PSD usable by the engine."""
    s = surfaces.read_profiles(_scan_csv(tmp_path)).psd().to_isotropic()
    assert isinstance(s, surfaces.PSD)
    lo, hi = s.q_range
    assert 0 < lo < hi and s.C(math.sqrt(lo * hi)) > 0 and s.C(hi * 2) == 0
    assert s.hrms() > 0 and s.rms_slope() > 0 and s.moment(1) == pytest.approx(s.hrms() ** 2)
    assert s.with_cutoff(q1=hi / 2).q1 == pytest.approx(hi / 2)
    c = s.cutoffs
    assert c.q_r == pytest.approx(s.q_r) and c.qL is not None and c.extrapolated is False


def test_several_files_pool_into_one_set(tmp_path):
    a, b = _scan_csv(tmp_path, 1, name="a.csv"), _scan_csv(tmp_path, 2, n=1024, name="b.csv")
    ps = surfaces.read_profiles([a, b])
    assert len(ps) == 4 and "a.csv" in ps.source and "b.csv" in ps.source
    assert len(surfaces.ProfileSet.concatenate([surfaces.read_profiles(a), surfaces.read_profiles(b)])) == 4
    p1 = ps.psd()  # profiles of different lengths share the log bins
    assert p1.n_profiles == 4 and p1.q[0] == pytest.approx(2e2, rel=0.1)


def test_selfaffine_and_psd_keep_their_interface():
    s = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e7, hrms=20e-6)
    assert s.hrms() == pytest.approx(20e-6)
    assert s.q_range == (1e3, 1e7) and s.q_r is None and not s.extrapolated
    t = s.tabulate()
    p = surfaces.PSD(t.q, t.C_values, q_r=None, extrapolated=False, source="t")
    assert p.hrms() == pytest.approx(20e-6, rel=1e-9)
    assert p.rms_slope() == pytest.approx(s.rms_slope(), rel=1e-9)
    with pytest.raises(surfaces.InputError, match="extrapolate"):
        p.with_cutoff(q1=1e8)
    assert s.extrapolate(2e7).q1 == 2e7


def test_analysis_functions_carry_citations():
    for fn in (surfaces.abel_forward, surfaces.gamma_factor, surfaces.fit_self_affine, surfaces.fit_rolloff,
               surfaces.reliability_limit, surfaces.mpd, surfaces.etd, surfaces.hdc, surfaces.fit_hdc,
               surfaces.synthesize_map, surfaces.synthesize_profiles, surfaces.example_road,
               surfaces.PSD1D.to_isotropic, surfaces.PSD.extrapolate, surfaces.ProfileSet.psd,
               surfaces.HeightMap.psd):
        assert frictioncite.citations_of(fn), fn.__qualname__
    assert "iso:13473-1:2019" in surfaces.mpd.__citations__


def test_every_bad_argument_is_an_input_error():
    s = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, hrms=1e-6)
    with pytest.raises(surfaces.InputError):
        surfaces.synthesize_map(s, 3)
    with pytest.raises(surfaces.InputError, match="method"):
        surfaces.PSD1D([1.0, 2.0, 3.0, 4.0, 5.0], [5.0, 4.0, 3.0, 2.0, 1.0]).to_isotropic(method="magic")
    with pytest.raises(surfaces.InputError, match="too few"):
        surfaces.PSD1D([1.0, 2.0, 3.0], [3.0, 2.0, 1.0]).to_isotropic()
    with pytest.raises(surfaces.InputError, match="hurst"):
        surfaces.PSD([1e3, 1e4], [1e-20, 1e-24]).extrapolate(1e6, hurst=1.5)
    with pytest.raises(surfaces.InputError):
        surfaces.abel_forward(s, [-1.0])


def test_plots_return_figures(tmp_path):
    truth = surfaces.SelfAffine(hurst=0.8, q0=2e3, q1=5e5, hrms=50e-6, qL=2e2)
    ps = surfaces.synthesize_profiles(truth, n_profiles=2, n=2048, seed=1)
    p1 = ps.psd()
    iso = p1.to_isotropic().extrapolate(1e7)
    figs = [
        plots.plot_profiles(ps),
        plots.plot_psd1d(p1, fit=surfaces.fit_self_affine(p1, 5e3, 5e4)),
        plots.plot_psd(iso, fit=surfaces.fit_rolloff(iso.with_cutoff(q1=iso.q_r))),
        plots.plot_psd(truth, fit=surfaces.fit_self_affine(truth, 3e3, 3e5)),
        plots.plot_height_map(surfaces.synthesize_map(truth, 64, seed=1)),
        plots.plot_hdc(surfaces.hdc(ps), fit=surfaces.fit_hdc(ps)),
    ]
    assert matplotlib.get_backend().lower() == "agg"
    for i, fig in enumerate(figs):
        ax = fig.axes[0]
        assert isinstance(fig, matplotlib.figure.Figure) and (ax.lines or ax.images)
        fig.savefig(tmp_path / f"f{i}.png")
        matplotlib.pyplot.close(fig)
    # cut-offs are marked (vertical lines with labels)
    labels = [t.get_text() for t in figs[2].axes[0].texts]
    assert {"$q_L$", "$q_0$", "$q_r$", "$q_1$"} <= set(labels)


def test_the_texture_functions_take_the_options_of_the_computations_behind_them():
    """surfaces.mpd / hdc / fit_hdc accept profiles in any form and hand the options to the computations that
    ProfileSet.mpd() and .hdc() use too: the two keep the same options and defaults."""
    import inspect

    from surfaces import profile_metrics, texture

    for public, core in ((texture.mpd, profile_metrics.mean_profile_depth),
                         (texture.hdc, profile_metrics.height_difference_correlation),
                         (texture.fit_hdc, profile_metrics.fit_height_difference_correlation)):
        options = [(p.name, p.default, p.kind) for p in list(inspect.signature(public).parameters.values())[1:]]
        assert options == [(p.name, p.default, p.kind) for p in list(inspect.signature(core).parameters.values())[1:]]
