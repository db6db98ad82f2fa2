"""Views: matplotlib plots of band contributions and sweep results; pyvista 3D contact rendering."""

import math

import numpy as np
import pytest

import materials
import persson
import surfaces
from persson import sweeps, views
from persson.errors import InputError


@pytest.fixture(scope="module")
def model():
    s = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e7, hrms=0.35e-3, qL=2 * math.pi / 0.1)
    return persson.Model(s, materials.example_tread())


def _png(path):
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 5000
    return data


def test_plot_bands_and_continuous(model, tmp_path):
    t = sweeps.bands(model, "decades", n=5, params={"pressure": [0.1e6, 0.5e6]}, speed=[0.01, 1.0])
    fig = views.plot_bands(t, speed=1.0)
    assert len(fig.axes[0].patches) == 2 * 2 * 5
    _png(views.save_figure(fig, tmp_path / "bands.png"))
    c = sweeps.bands(model, "continuous", speed=1.0)
    _png(views.save_figure(views.plot_bands(c), tmp_path / "continuous.png"))


def test_plot_sweep(model, tmp_path):
    t = sweeps.grid(model, {"pressure": [0.1e6, 0.3e6, 0.5e6], "temperature": [0.0, 20.0]}, speed=1.0)
    fig = views.plot_sweep(t, x="pressure", y=["mu", "contact_area"])
    assert len(fig.axes) == 2 and len(fig.axes[0].lines) == 2
    _png(views.save_figure(fig, tmp_path / "sweep.png"))
    with pytest.raises(InputError, match="x: no column"):
        views.plot_sweep(t, x="surface.q1")


def test_contact_regions_cover_the_area_fraction():
    z = np.random.default_rng(1).standard_normal((64, 80))
    for a in (0.0, 0.013, 0.25, 1.0):
        mask, thr = views.contact_regions(z, a)
        assert mask.mean() == pytest.approx(a, abs=1 / z.size)
        assert np.all(z[mask] > thr)
    with pytest.raises(InputError, match="area_fraction"):
        views.contact_regions(z, 1.5)


def test_synthesized_heights_have_the_psd_rms():
    s = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=64e3, hrms=20e-6)
    z, dx = views.synthesize_heights(s, n=256, seed=3)
    assert z.shape == (256, 256) and dx == pytest.approx(2 * math.pi / 1e3 / 256)
    assert np.std(z) == pytest.approx(20e-6, rel=0.15)  # one realization of a Gaussian field
    z2, _ = views.synthesize_heights(s, n=256, seed=3)
    np.testing.assert_array_equal(z, z2)


def test_contact_view_renders_a_png_off_screen(model, tmp_path):
    try:
        cv = views.contact_view(model, tmp_path / "contact.png", magnification=20.0, n=128, seed=0,
                                window_size=(640, 480))
    except RuntimeError as exc:  # no OpenGL for off-screen rendering on this machine
        pytest.skip(f"pyvista off-screen rendering unavailable: {exc}")
    _png(cv.path)
    r = model.friction(1.0, pressure=0.3e6)
    P = np.interp(math.log(20.0 * r.q[0]), np.log(r.q), r.area_q[0])
    assert cv.area_fraction == pytest.approx(P, rel=1e-12)
    assert cv.drawn_fraction == pytest.approx(P, abs=1 / 128**2)
    assert cv.q == pytest.approx(20.0 * r.q[0])
    with pytest.raises(InputError, match="magnification"):
        views.contact_view(model, tmp_path / "x.png", magnification=1e9)
