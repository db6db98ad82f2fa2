"""Sweeps by length-scale band and parameter (issue 8): band modes, scaling, parameter grids, table, CLI."""

import math
import time

import numpy as np
import pytest

import materials
import persson
import surfaces
from persson import sweeps
from persson import effects as fx
from persson.errors import InputError

SPEEDS = np.array([1e-4, 1e-2, 1.0])


@pytest.fixture(scope="module")
def road():
    # the example road's parameters (surfaces.example_road): self-affine with a plateau below the roll-off
    return surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e7, hrms=0.35e-3, qL=2 * math.pi / 0.1)


@pytest.fixture(scope="module")
def model(road):
    return persson.Model(road, materials.example_tread(), effects=[fx.Adhesion()])


# ------------------------------------------------------------------------------------------------- mode (a)
@pytest.mark.parametrize("kind, n", [("decades", 6), ("decades", None), ("linear_q", 5), ("linear_length", 4),
                                     ([62.83185307179586, 3.3e3, 4.7e4, 9.1e5, 1e7], None), ("continuous", None)])
def test_restrict_bands_add_up_to_the_total(model, kind, n):
    t = sweeps.bands(model, kind, n=n, mode="restrict", speed=SPEEDS, params={"pressure": [0.1e6, 0.5e6]})
    # the sweep makes the band edges wavevector nodes of the engine (exact band sums)
    edges = () if kind == "continuous" else tuple(np.ravel(sweeps.band_edges(kind, model.surface.q_range, n)))
    r = model.replace(grid=persson.GridSettings(extra_q=edges)).friction(SPEEDS, temperature=20.0, pressure=0.5e6)
    for pt in (0, 1):
        for v in SPEEDS:
            rows = t.where(point=pt, speed_m_s=v, mode="restrict")
            if kind == "continuous":
                total_h = model.friction(v, pressure=(0.1e6, 0.5e6)[pt]).mu_hysteresis
                total_mu = model.friction(v, pressure=(0.1e6, 0.5e6)[pt]).mu
            else:
                tot = t.where(point=pt, speed_m_s=v, mode="total")
                assert len(tot) == 1
                total_h, total_mu = tot["mu_hysteresis"][0], tot["mu"][0]
            assert rows["mu_hysteresis"].sum() == pytest.approx(total_h, rel=1e-6)
            # adhesion is attributed to the band ending at q1, so mu adds up too
            assert rows["mu"].sum() == pytest.approx(total_mu, rel=1e-6)
            assert rows["fraction"].sum() == pytest.approx(1.0, rel=1e-6)
            assert np.all(rows["mu_hysteresis"] >= 0)
    # the totals are the engine's
    tot = t.where(point=1, mode="total") if kind != "continuous" else None
    if tot is not None:
        np.testing.assert_array_equal(tot["mu"], r.mu)
        np.testing.assert_array_equal(tot["contact_area"], r.contact_area)


def test_band_contributions_are_additive_when_a_band_is_split(model):
    r = model.friction(SPEEDS, pressure=0.3e6)
    whole = sweeps.band_contributions(r, [[1e3, 2e5]])
    split = sweeps.band_contributions(r, [[1e3, 1.234e4], [1.234e4, 2e5]])
    np.testing.assert_allclose(split.sum(axis=1), whole[:, 0], rtol=1e-12)
    # edges on grid nodes give the engine's own partial sums: differences of its cumulative friction
    q = r.q
    np.testing.assert_allclose(r.mu_cumulative[:, -1], r.mu_hysteresis, rtol=1e-12)
    band = sweeps.band_contributions(r, [[q[10], q[39]]])[:, 0]
    np.testing.assert_allclose(band, r.mu_cumulative[:, 39] - r.mu_cumulative[:, 10], rtol=1e-12)


def test_band_contributions_match_an_independent_quadrature(model):
    """Bands of the full surface against an adaptive ODE quadrature (persson.engine.reference) at the band edges."""
    from persson.engine.reference import reference_friction

    edges = np.geomspace(*model.surface.q_range, 4)
    t = sweeps.bands(model, edges, speed=[1e-3, 1.0], params={"pressure": [0.3e6]})
    mu_at = reference_friction(model.surface, model.material, [1e-3, 1.0], 20.0, 0.3e6, gamma=model.gamma,
                               q_eval=edges).mu_at
    for i, v in enumerate([1e-3, 1.0]):
        rows = t.where(speed_m_s=v, mode="restrict")
        # the accuracy target is relative to the friction coefficient: 1e-4 of mu, ten times below 1e-3
        np.testing.assert_allclose(rows["mu_hysteresis"], np.diff(mu_at[i]), rtol=0, atol=1e-4 * mu_at[i, -1])


# ------------------------------------------------------------------------------------------------- mode (b)
def test_separate_bands_add_up_to_at_least_the_total(model):
    t = sweeps.bands(model, "decades", n=6, mode="both", speed=SPEEDS, params={"pressure": [0.1e6, 0.9e6]})
    for pt in (0, 1):
        for v in SPEEDS:
            total = t.where(point=pt, speed_m_s=v, mode="total")
            sep = t.where(point=pt, speed_m_s=v, mode="separate")
            res = t.where(point=pt, speed_m_s=v, mode="restrict")
            assert len(sep) == len(res) == 6
            assert sep["mu_hysteresis"].sum() >= total["mu_hysteresis"][0]
            assert sep["mu"].sum() >= total["mu"][0]
            # a band alone has at least the contact area it has under the longer wavelengths
            assert np.all(sep["contact_area"] >= res["contact_area"] * (1 - 1e-3))
            # the first band starts at q0 in both modes: same physics, only the q grid differs
            assert sep["mu_hysteresis"][0] == pytest.approx(res["mu_hysteresis"][0], rel=2e-3)


def test_band_surface_restricts_a_plateau_model(road):
    qa, qb = 200.0, 5e3  # across the roll-off q0 = 1257 rad/m
    b = sweeps.BandSurface(road, qa, qb)
    q = np.geomspace(50, 2e4, 400)
    inside = (q >= qa) & (q <= qb)
    np.testing.assert_array_equal(b.C(q)[inside], road.C(q)[inside])
    assert np.all(b.C(q)[~inside] == 0)
    assert b.q_range == (qa, qb)
    # with_cutoff(q0=qa) would move the roll-off and change C inside the band: why BandSurface exists
    assert not np.allclose(road.with_cutoff(q0=qa, q1=qb).C(q[inside]), road.C(q[inside]), rtol=1e-6, atol=0)
    assert b.hrms() < road.hrms()


@pytest.mark.parametrize("effects", [
    (fx.FlashTemperature(), fx.Adhesion()),
    (fx.Microtexture(q1=1e7), fx.Adhesion()),
    (fx.Wet(lift=1.0, alpha=100.0),),
], ids=["flash+adhesion", "microtexture+adhesion", "wet-lift"])
def test_bands_with_builtin_effects(road, effects):
    """Flash temperature (T_q), a tail added by an effect (bands follow the range the engine integrates) and a
    fluid carrying part of the load (the load share scales the integrand)."""
    measured = road.tabulate().with_cutoff(q1=1e5)
    psd = surfaces.PSD(measured.q, measured.C_values, q_r=1e5, source="road to 1e5 rad/m")
    m = persson.Model(psd, materials.example_tread(), effects=effects)
    t = sweeps.bands(m, "decades", mode="both", speed=SPEEDS, pressure=0.2e6)
    q1 = 1e7 if effects[0].name == "microtexture" else 1e5
    assert sweeps.effective_q_range(m, SPEEDS, 20.0, 0.2e6)[1] == pytest.approx(q1)
    for v in SPEEDS:
        tot = t.where(speed_m_s=v, mode="total")
        res = t.where(speed_m_s=v, mode="restrict")
        sep = t.where(speed_m_s=v, mode="separate")
        assert res["q_high"][-1] == pytest.approx(q1) and tot["q_high"][0] == pytest.approx(q1)
        assert res["mu_hysteresis"].sum() == pytest.approx(tot["mu_hysteresis"][0], rel=1e-6)
        assert res["mu"].sum() == pytest.approx(tot["mu"][0], rel=1e-6)
        assert sep["mu"].sum() >= tot["mu"][0]


# --------------------------------------------------------------------------------------- large-G scaling
@pytest.mark.parametrize("H", [0.5, 0.8])
def test_dmu_dlogq_follows_the_large_G_scaling(H):
    r"""Frequency-independent modulus on a self-affine surface, G >> 1.

    G(q) = (pi/4) (|E|/((1-nu^2) sigma0))^2 C0 (q^a - q0^a) / a with a = 2 - 2H, so G ~ q^(2-2H);
    P = erf(1/(2 sqrt G)) -> 1/sqrt(pi G); d mu/d ln q = 2 q^4 C P E''/((1-nu^2) sigma0) ~ q^(2-2H) P,
    hence d mu/d log q ~ q^(2-2H) q^(-(1-H)) = q^(1-H). With the q0 term kept, the local log-log slope is
    a - (a/2) q^a / (q^a - q0^a).
    """
    q0 = 1e3
    s = surfaces.SelfAffine(hurst=H, q0=q0, q1=1e9, hrms=20e-6)
    m = persson.Model(s, materials.ConstantModulus(E_storage=5e6, E_loss=2e6), gamma=1.0)
    p = 0.03e6
    t = sweeps.bands(m, "continuous", speed=1.0, pressure=p)
    G = m.friction(1.0, pressure=p).G_q[0]
    q, d = t["q"], t["dmu_dlog10q"]
    assert np.all(np.diff(t["q"]) > 0) and len(q) == G.size
    big = (G > 100) & (q >= 1e6)
    assert big.sum() > 40                                # three decades of nodes
    slope = np.polyfit(np.log(q[big]), np.log(d[big]), 1)[0]
    assert slope == pytest.approx(1 - H, abs=0.01)
    a = 2 - 2 * H
    local = np.gradient(np.log(d), np.log(q))
    inner = (G > 100) & (np.arange(q.size) > 0) & (np.arange(q.size) < q.size - 1)
    expected = a - 0.5 * a * q[inner] ** a / (q[inner] ** a - q0**a)
    np.testing.assert_allclose(local[inner], expected, atol=2e-3)
    # every decade carries a comparable share: successive decades grow by about 10^(1-H)
    dec = sweeps.bands(m, [1e6, 1e7, 1e8, 1e9], mode="restrict", speed=1.0, pressure=p).where(mode="restrict")
    ratios = dec["mu_hysteresis"][1:] / dec["mu_hysteresis"][:-1]
    np.testing.assert_allclose(ratios, 10 ** (1 - H), rtol=0.03)


# ------------------------------------------------------------------------------------------------- grids
def test_grid_over_surface_material_effect_and_conditions(model):
    params = {"pressure": "0.1e6:0.5e6:2", "surface.q1": [1e6, 1e7], "adhesion.tau_f0": [1e6, 3e6],
              "material.wlf.C1": [8.86]}
    t = sweeps.grid(model, params, speed=SPEEDS, temperature=10.0)
    assert len(t) == 2 * 2 * 2 * 1 * SPEEDS.size
    assert t.names[:8] == ("point", "surface.q1", "adhesion.tau_f0", "material.wlf.C1", "speed_m_s",
                           "temperature_C", "pressure_Pa", "mu")
    for name in sweeps.OUTPUTS:
        assert name in t and np.all(np.isfinite(t[name]))
    row = t.where(pressure_Pa=0.5e6, **{"surface.q1": 1e6, "adhesion.tau_f0": 3e6})
    m = model.replace(surface=model.surface.with_cutoff(q1=1e6),
                      effects=(model.effect("adhesion").with_parameters(tau_f0=3e6),))
    r = m.friction(SPEEDS, temperature=10.0, pressure=0.5e6)
    np.testing.assert_array_equal(row["speed_m_s"], SPEEDS)
    np.testing.assert_array_equal(row["mu"], r.mu)
    np.testing.assert_array_equal(row["mu_adhesion"], r.mu_adhesion)
    np.testing.assert_array_equal(row["contact_area"], r.contact_area)
    assert np.all(row["mu_adhesion"] > 0)
    # speed swept as a parameter: one engine call per point, same table
    t2 = sweeps.grid(model, {"speed": SPEEDS, "pressure": [0.1e6]})
    t3 = sweeps.grid(model, {"pressure": [0.1e6]}, speed=SPEEDS)
    assert t2.equals(t3)


def test_set_parameter_rebuilds_components(road):
    m = persson.Model(road, materials.example_tread(), effects=[fx.Adhesion()])
    h = sweeps.set_parameter(m, "surface.hurst", 0.6).surface
    assert h.hurst == 0.6 and h.hrms() == pytest.approx(road.hrms(), rel=1e-12) and h.qL == road.qL
    assert sweeps.set_parameter(m, "surface.hrms", 1e-3).surface.hrms() == pytest.approx(1e-3, rel=1e-12)
    q1 = sweeps.set_parameter(m, "surface.q1", 1e6).surface
    assert q1.q1 == 1e6 and q1.C0 == road.C0
    assert sweeps.set_parameter(m, "material.wlf.C1", 10.0).material.wlf.C1 == 10.0
    assert sweeps.set_parameter(m, "material.thermal.conductivity", 0.3).material.thermal.conductivity == 0.3
    assert sweeps.set_parameter(m, "grid.q_per_decade", 16.0).grid.q_per_decade == 16
    assert sweeps.set_parameter(m, "gamma", 1.0).gamma == 1.0
    assert sweeps.set_parameter(m, "effects.adhesion.tau_f0", 5e5).effect("adhesion").tau_f0 == 5e5
    cm = persson.Model(road, materials.ConstantModulus(5e6, 2e6))
    assert sweeps.set_parameter(cm, "material.E_loss", 1e6).material.E_loss == 1e6
    tab = persson.Model(road.tabulate(), materials.ConstantModulus(5e6, 2e6))
    assert sweeps.set_parameter(tab, "surface.hrms", 1e-3).surface.hrms() == pytest.approx(1e-3, rel=1e-9)
    assert sweeps.set_parameter(tab, "surface.q1", 1e6).surface.q1 == 1e6
    # hrms is applied after q1 at the same point, so it holds over the final support
    t = sweeps.grid(m, {"surface.hrms": [1e-4], "surface.q1": [1e6]}, speed=1.0)
    assert len(t) == 1


# ------------------------------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("call, match", [
    (lambda m: sweeps.bands(m, [[1e4, 1e4]]), r"bands: band 0 is empty"),
    (lambda m: sweeps.bands(m, [[1e5, 1e3]]), r"bands: band 0 is empty"),
    (lambda m: sweeps.bands(m, [[10.0, 1e3]]), r"bands: band 0 .* outside"),
    (lambda m: sweeps.bands(m, [1e3, 1e5, 1e8]), r"bands: band 1 .* outside"),
    (lambda m: sweeps.bands(m, "octaves"), r"bands: unknown band kind"),
    (lambda m: sweeps.bands(m, "decades", n=0), r"^n:"),
    (lambda m: sweeps.bands(m, "continuous", mode="separate"), r"band_mode"),
    (lambda m: sweeps.bands(m, "decades", mode="sideways"), r"band_mode"),
    (lambda m: sweeps.grid(m, {"surface.roughness": [1.0]}), r"unknown parameter name 'surface.roughness'"),
    (lambda m: sweeps.grid(m, {"flux_capacitor": [1.0]}), r"unknown parameter name 'flux_capacitor'"),
    (lambda m: sweeps.grid(m, {"adhesion.tau_x": [1.0]}), r"unknown parameter 'adhesion.tau_x'"),
    (lambda m: sweeps.grid(m, {"pressure": "0.1e6:0.9e6"}), r"params\['pressure'\]: malformed range"),
    (lambda m: sweeps.grid(m, {"pressure": "0.1e6:0.9e6:x"}), r"params\['pressure'\]: malformed range"),
    (lambda m: sweeps.grid(m, {"pressure": "1:2:3:cubic"}), r"params\['pressure'\]: malformed range"),
    (lambda m: sweeps.grid(m, {"pressure": []}), r"params\['pressure'\]: expected at least one value"),
    (lambda m: sweeps.grid(m, {"pressure": [-1.0]}), r"pressure: expected a nominal pressure > 0"),
    (lambda m: sweeps.grid(m, {"speed": [0.0]}), r"params\['speed'\]"),
    (lambda m: sweeps.grid(m, {"surface.hurst": [1.5]}), r"surface.hurst"),
    (lambda m: sweeps.grid(m, {}, scheduler="cloud"), r"scheduler"),
    (lambda m: sweeps.parse_param("pressure:1:2:3"), r"--param 'pressure:1:2:3': expected NAME=VALUES"),
    (lambda m: sweeps.parse_param("pressure=1:2:0"), r"--param 'pressure=1:2:0': malformed range"),
])
def test_bad_input_raises_input_error_naming_the_argument(model, call, match):
    with pytest.raises(InputError, match=match):
        call(model)


def test_parse_param_forms():
    assert sweeps.parse_param("pressure=0.1e6:0.9e6:5")[1].tolist() == pytest.approx([1e5, 3e5, 5e5, 7e5, 9e5])
    name, v = sweeps.parse_param("surface.q1=1e5:1e7:3:log")
    assert name == "surface.q1" and v.tolist() == pytest.approx([1e5, 1e6, 1e7])
    assert sweeps.parse_param("temperature_C=0,20,40") == ("temperature", pytest.approx([0.0, 20.0, 40.0]))
    assert sweeps.parse_param("gamma=1")[1].tolist() == [1.0]


# ------------------------------------------------------------------------------------------ table, progress
def test_table_saves_to_csv_and_reads_back_exactly(model, tmp_path):
    t = sweeps.bands(model, "decades", n=3, speed=SPEEDS)
    path = t.to_csv(tmp_path / "out" / "bands.csv")
    back = sweeps.read_table(path)
    assert back.equals(t)
    assert back["mode"].tolist()[:3] == ["total"] * 3 and back["band"].dtype.kind == "i"
    assert back.comments == t.comments and any("bands: decades" in c for c in t.comments)
    assert [p.name for p in path.parent.iterdir()] == ["bands.csv"]  # no temporary file left behind
    rows = t.rows()
    assert len(rows) == len(t) and rows[0]["mode"] == "total" and isinstance(rows[0]["mu"], float)


def test_interrupted_sweep_keeps_the_points_already_computed(model, tmp_path):
    seen = []

    def stop_after_two(done, total):
        seen.append((done, total))
        if done == 2:
            raise KeyboardInterrupt

    ck = tmp_path / "checkpoint.csv"
    with pytest.raises(sweeps.SweepInterrupted) as info:
        sweeps.grid(model, {"pressure": [0.1e6, 0.2e6, 0.3e6, 0.4e6]}, speed=SPEEDS, progress=stop_after_two,
                    checkpoint=ck)
    exc = info.value
    assert isinstance(exc, KeyboardInterrupt)
    assert (exc.done, exc.total) == (2, 4) and seen == [(1, 4), (2, 4)]
    assert len(exc.table) == 2 * SPEEDS.size
    np.testing.assert_array_equal(np.unique(exc.table["pressure_Pa"]), [0.1e6, 0.2e6])
    assert any(c.startswith("PARTIAL") for c in exc.table.comments)
    assert exc.checkpoint == ck and sweeps.read_table(ck).equals(exc.table)
    full = sweeps.grid(model, {"pressure": [0.1e6, 0.2e6, 0.3e6, 0.4e6]}, speed=SPEEDS, checkpoint=ck,
                       progress=False)
    assert full.take(np.arange(len(exc.table))).equals(exc.table)
    assert sweeps.read_table(ck).equals(full)


def test_progress_bar_is_plain_text(capsys):
    import io

    buf = io.StringIO()
    bar = sweeps.Progress(4, True, stream=buf)
    for i in range(1, 5):
        bar.update(i)
    text = buf.getvalue()
    assert "4/4 (100 %)" in text and "[" in text and "#" in text


# ------------------------------------------------------------------------------------------------- CLI
def _write_case(tmp_path):
    """A case with the example road and tread (PSD file when surfaces.example_road is not there yet)."""
    if hasattr(surfaces, "example_road"):
        surface = '[surface]\nexample = "road"\n'
    else:
        surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e7, hrms=0.35e-3,
                            qL=2 * math.pi / 0.1).to_csv(tmp_path / "psd.csv")
        surface = '[surface]\npsd = "psd.csv"\n'
    (tmp_path / "case.toml").write_text('name = "sweep-example"\n' + surface + '[material]\nexample = "tread"\n'
                                        "[conditions]\nspeeds_m_s = [1e-4, 1e-2, 1.0]\n")
    return tmp_path / "case.toml"


def test_cli_sweep_bands_by_pressure_writes_the_python_table(tmp_path, capsys):
    from persson.case import read_case
    from persson.commands.cli import main

    case = _write_case(tmp_path)
    out = tmp_path / "results.csv"
    t0 = time.perf_counter()
    rc = main(["sweep", str(case), "--bands", "decades", "--n-bands", "6", "--param", "pressure=0.1e6:0.9e6:3",
               "-o", str(out), "--no-progress"])
    elapsed = time.perf_counter() - t0
    assert rc == 0
    printed = capsys.readouterr().out
    assert f"wrote {out.resolve()}" in printed
    t = sweeps.read_table(out)
    for col in ("q_low", "q_high", "mode", "pressure_Pa", "speed_m_s", *sweeps.OUTPUTS):
        assert col in t
    assert len(t) == 3 * 3 * (1 + 6 + 6)
    assert sorted(set(t["mode"])) == ["restrict", "separate", "total"]
    spec = read_case(case)
    py = sweeps.bands(spec.model, "decades", n=6, params={"pressure": "0.1e6:0.9e6:3"}, speed=spec.speeds,
                      temperature=spec.temperature)
    assert py.equals(t)
    print(f"persson sweep, 6 decade bands x 3 pressures x 3 speeds (in process): {elapsed:.2f} s")


def test_cli_sweep_plain_grid_with_plot(tmp_path, capsys):
    from persson.commands.cli import main

    case = _write_case(tmp_path)
    out = tmp_path / "grid.csv"
    rc = main(["sweep", str(case), "--param", "temperature=0,20", "--param", "surface.q1=1e5:1e7:3:log",
               "--speeds", "1e-3:1:4", "-o", str(out), "--plot", "--no-progress"])
    assert rc == 0
    printed = capsys.readouterr().out
    assert str(out.with_suffix(".png").resolve()) in printed
    t = sweeps.read_table(out)
    assert len(t) == 2 * 3 * 4 and "mode" not in t and "surface.q1" in t
    assert out.with_suffix(".png").stat().st_size > 1000


@pytest.mark.parametrize("argv, match", [
    (["--param", "pressure=0.1e6:0.9e6"], "--param 'pressure=0.1e6:0.9e6': malformed range"),
    (["--param", "nonsense=1"], "unknown parameter name 'nonsense'"),
    (["--bands", "decades", "--n-bands", "0"], "n: expected"),
    (["--bands", "1e3,1e3"], "bands: band 0 is empty"),
    (["--bands", "1,1e3"], "outside"),
])
def test_cli_sweep_bad_input_exits_2_naming_the_argument(tmp_path, capsys, argv, match):
    from persson.commands.cli import main

    case = _write_case(tmp_path)
    assert main(["sweep", str(case), "-o", str(tmp_path / "x.csv"), *argv]) == 2
    assert match in capsys.readouterr().err
    assert not (tmp_path / "x.csv").exists()
