"""Readers, preparation steps and bad input of :mod:`surfaces` (issue 3, items 1-2 and Must show 5)."""

import math

import numpy as np
import pytest

import surfaces


def _write(path, text):
    path.write_text(text)
    return path


# ---------------------------------------------------------------------- profile CSV


def test_read_profile_csv_units_dropouts_comments(tmp_path):
    path = _write(tmp_path / "scan.csv", "# instrument: test\nx_mm,z1_mm,z2_um\n0,0.1,100\n0.5,,200\n"
                                         "# a comment line\n1.0,0.3,NaN\n1.5,0.2,150\n")
    ps = surfaces.read_profiles(path)
    assert len(ps) == 2 and ps.names == ("z1_mm", "z2_um")
    np.testing.assert_allclose(ps[0].x, [0, 0.5e-3, 1.0e-3, 1.5e-3])
    np.testing.assert_allclose(ps[1].z, [100e-6, 200e-6, np.nan, 150e-6])
    np.testing.assert_allclose(ps.dropout_fraction, [0.25, 0.25])
    assert str(path) in ps[0].where and "z1_mm" in ps[0].where


def test_read_profile_csv_single_column_in_metres(tmp_path):
    path = _write(tmp_path / "m.csv", "x_m,z_m\n0,1e-4\n1e-3,2e-4\n2e-3,1.5e-4\n")
    p = surfaces.read_profiles(path)[0]
    assert p.dx == pytest.approx(1e-3) and p.z[1] == pytest.approx(2e-4)


BAD_CSV = {
    "empty": ("", "empty file"),
    "one column": ("x_mm\n0\n1\n", "found columns ['x_mm']"),
    "non-monotonic x": ("x_mm,z_mm\n0,1\n2,1\n1,3\n", "line 4, column x_mm: x must be strictly increasing"),
    "all-NaN profile": ("x_mm,z1_mm,z2_mm\n0,1,\n1,2,NaN\n2,3,\n", "column z2_mm: all values are missing"),
    "unknown unit": ("x_mm,z_in\n0,1\n1,2\n", "column z_in: unknown length unit 'in'"),
    "unknown x unit": ("x_ft,z_mm\n0,1\n1,2\n", "column x_ft: unknown length unit 'ft'"),
    "text cell": ("x_mm,z_mm\n0,1\n1,abc\n", "line 3, column z_mm: expected a number"),
    "ragged row": ("x_mm,z_mm\n0,1\n1,2,3\n", "line 3: expected 2 fields"),
    "no data": ("x_mm,z_mm\n", "no data rows"),
    "missing x": ("x_mm,z_mm\n0,1\n,2\n", "line 3, column x_mm: x is missing"),
}


@pytest.mark.parametrize("case", sorted(BAD_CSV))
def test_bad_profile_csv_names_file_and_column(tmp_path, case):
    """Must show: bad input raises InputError (a ValueError) naming the file and the column/line."""
    text, expected = BAD_CSV[case]
    path = _write(tmp_path / "bad.csv", text)
    with pytest.raises(surfaces.InputError) as err:
        surfaces.read_profiles(path)
    assert isinstance(err.value, ValueError)
    assert str(path) in str(err.value)
    assert expected in str(err.value)


def test_profile_too_short_for_one_mpd_segment(tmp_path):
    """Must show: a profile shorter than one 100 mm MPD segment is refused, naming file and column."""
    x = np.arange(0, 80.0, 0.5)
    rows = "\n".join(f"{a},{math.sin(a):.4f}" for a in x)
    path = _write(tmp_path / "short.csv", "x_mm,z3_mm\n" + rows + "\n")
    with pytest.raises(surfaces.InputError, match=r"short\.csv, column z3_mm: .*shorter than one MPD segment"):
        surfaces.mpd(surfaces.read_profiles(path))


def test_missing_file_and_unknown_format(tmp_path):
    with pytest.raises(surfaces.InputError, match="not found"):
        surfaces.read_profiles(tmp_path / "nope.csv")
    path = _write(tmp_path / "a.csv", "x_mm,z_mm\n0,1\n1,2\n")
    with pytest.raises(surfaces.InputError, match="format"):
        surfaces.read_profiles(path, format="xlsx")


# ---------------------------------------------------------------------- CAPTIF export

CAPTIF_HEADER = ("Road Name\tCAPTIF\t\r\nRef Station\t0\t\r\nStart Pos (m)\t0\t\r\nEnd Pos (m)\t0\t\r\n"
                 "Direction\tincreasing\t\r\nWheel Path\tLeft\t\r\nDate\t11/10/2021\t\r\nFile No.\t0\t\r\n"
                 "Current Pos\t0.0\t\r\n*****DATA*****\t\t\r\nData Point No:\tDistance (mm)\tDepth (mm)\r\n")


def _captif(tmp_path, z_mm, dx_mm=0.0375, name="c.dat"):
    lines = [f"{i + 1:.3f}\t{i * dx_mm:.3f}\t{'NaN' if np.isnan(z) else f'{z:.3f}'}" for i, z in enumerate(z_mm)]
    return _write(tmp_path / name, CAPTIF_HEADER + "\r\n".join(lines) + "\r\n")


def test_read_captif_export_with_plates(tmp_path):
    n = 4000
    z = 0.5 * np.sin(np.arange(n) * 0.05)
    z[:400] = 47.0            # reference plate at the start
    z[-300:] = 47.0           # and at the end
    z[1000:1010] = np.nan     # dropouts
    path = _captif(tmp_path, z)
    raw = surfaces.read_profiles(path, trim_plates=False)
    assert raw.meta["Road Name"] == "CAPTIF" and raw.meta["File No."] == "0"
    assert raw[0].n == n and raw[0].dropout_fraction == pytest.approx(10 / n)
    assert raw[0].is_uniform  # 0.0375 mm written as 0.037/0.038: uniform up to rounding
    road = surfaces.read_profiles(path)  # plates trimmed by default
    assert np.nanmax(road[0].z) < 1e-3
    assert road[0].x[0] == pytest.approx(400 * 0.0375e-3 + 2e-3, abs=0.05e-3)
    assert road.meta["raw_dropout_fraction"] == pytest.approx(10 / n)


def test_captif_bad_value_names_line_and_column(tmp_path):
    path = _captif(tmp_path, np.zeros(50))
    text = path.read_text().replace("\t0.375\t0.000", "\t0.375\tabc")
    path.write_text(text)
    with pytest.raises(surfaces.InputError, match=r"c\.dat, line \d+, column 'Depth \(mm\)'"):
        surfaces.read_profiles(path, format="captif")


def test_captif_unknown_unit(tmp_path):
    path = _captif(tmp_path, np.zeros(20))
    path.write_text(path.read_text().replace("Depth (mm)", "Depth (in)"))
    with pytest.raises(surfaces.InputError, match=r"c\.dat, column 'Depth \(in\)': unknown length unit"):
        surfaces.read_profiles(path)


# ---------------------------------------------------------------------- arrays and preparation


def test_profiles_from_array_and_errors():
    ps = surfaces.profiles_from_array(np.ones((3, 10)), dx=0.1, x_unit="mm", z_unit="um")
    assert len(ps) == 3 and ps[0].dx == pytest.approx(1e-4) and ps[2].z[0] == pytest.approx(1e-6)
    with pytest.raises(surfaces.InputError, match="exactly one of dx= and x="):
        surfaces.profiles_from_array(np.ones(10))
    with pytest.raises(surfaces.InputError, match="unknown length unit"):
        surfaces.profiles_from_array(np.ones(10), dx=1.0, z_unit="inch")


def test_fill_dropouts_reports_and_refuses():
    x = np.arange(100) * 1e-4
    z = np.sin(x * 3e3)
    z[[0, 1, 50, 51, 99]] = np.nan
    ps = surfaces.profiles_from_array(z, x=x)
    filled = ps.fill_dropouts()
    assert filled[0].dropout_fraction == pytest.approx(0.05)  # kept after filling
    assert not np.isnan(filled[0].z).any()
    assert filled[0].z[0] == filled[0].z[2]                          # ends: nearest valid value
    assert filled[0].z[50] == pytest.approx(z[49] + (z[52] - z[49]) / 3)  # interior: linear
    assert "5.00% dropouts" in filled.history[-1]
    with pytest.raises(surfaces.InputError, match=r"array, column z1: 5\.0% of the samples are dropouts"):
        ps.fill_dropouts(max_fraction=0.02)
    with pytest.raises(surfaces.InputError, match="fill_dropouts"):
        ps.detrend("linear")


def test_detrend_resample_and_spikes():
    x = np.linspace(0, 1e-2, 1001)
    base = 1e-6 * np.sin(2 * np.pi * x / 1e-3)
    ps = surfaces.profiles_from_array(base + 3e-4 * x + 2.0 * x**2, x=x)
    flat = ps.detrend("quadratic")  # removes the parabola exactly: same as detrending the sine alone
    alone = surfaces.profiles_from_array(base, x=x).detrend("quadratic")
    np.testing.assert_allclose(flat[0].z, alone[0].z, atol=1e-15)
    assert np.max(np.abs(flat[0].z - base)) < 0.1 * np.max(np.abs(base))
    with pytest.raises(surfaces.InputError, match="detrend"):
        ps.detrend("cubic")
    coarse = surfaces.profiles_from_array(base, x=x).resample(5e-5)
    assert coarse[0].dx == pytest.approx(5e-5) and "mean" in coarse.history[-1]
    noisy = base + 3e-8 * np.random.default_rng(0).standard_normal(x.size)  # measured data are never exact
    spiky = noisy.copy()
    spiky[[100, 500]] += 5e-5
    cleaned = surfaces.profiles_from_array(spiky, x=x).remove_spikes()
    assert np.max(np.abs(cleaned[0].z - base)) < 2e-7
    assert "removed 2 spikes" in cleaned.history[-1]


def test_nonuniform_profile_is_resampled_for_the_psd():
    rng = np.random.default_rng(1)
    x = np.sort(rng.uniform(0, 0.1, 3000))
    ps = surfaces.profiles_from_array(np.sin(2 * np.pi * x / 0.01) * 1e-4, x=x)
    assert not ps[0].is_uniform
    p1 = ps.psd()
    assert any("resampled" in h for h in p1.history)
    peak = p1.q[np.argmax(p1.C_values)]
    assert peak == pytest.approx(2 * np.pi / 0.01, rel=0.1)


def test_psd_of_a_sine_has_its_variance():
    """A periodic sinusoid of amplitude a has variance a^2/2 = 2 int C1D dq."""
    n, L, a = 1024, 0.1, 1e-4
    x = np.arange(n) * L / n
    ps = surfaces.profiles_from_array(a * np.sin(2 * np.pi * 8 * x / L), x=x, periodic=True)
    p1 = ps.psd()
    assert p1.hrms() == pytest.approx(a / math.sqrt(2), rel=1e-6)


# ---------------------------------------------------------------------- height maps


def test_read_height_map_npy(tmp_path):
    z = np.arange(12.0).reshape(3, 4)
    np.save(tmp_path / "m.npy", z)
    hm = surfaces.read_height_map(tmp_path / "m.npy", dx=1e-6, unit="um")
    np.testing.assert_allclose(hm.z, z * 1e-6)
    assert hm.shape == (3, 4) and hm.dy == 1e-6
    with pytest.raises(surfaces.InputError, match="m.npy: give exactly one of unit="):
        surfaces.read_height_map(tmp_path / "m.npy", dx=1e-6)


@pytest.mark.parametrize("suffix", [".png", ".tif"])
def test_read_height_map_16bit_image(tmp_path, suffix):
    from skimage import io as skio

    img = (np.arange(64 * 64).reshape(64, 64) * 7 % 65536).astype(np.uint16)
    path = tmp_path / f"map{suffix}"
    skio.imsave(path, img, check_contrast=False)
    hm = surfaces.read_height_map(path, dx=2e-6, height_scale=1e-9, offset=100)
    np.testing.assert_allclose(hm.z, (img.astype(float) - 100) * 1e-9)
    with pytest.raises(surfaces.InputError, match=rf"map\{suffix}: height_scale="):
        surfaces.read_height_map(path, dx=2e-6)


def test_height_map_bad_input(tmp_path):
    from skimage import io as skio

    skio.imsave(tmp_path / "rgb.png", np.zeros((8, 8, 3), dtype=np.uint8), check_contrast=False)
    with pytest.raises(surfaces.InputError, match="single-channel"):
        surfaces.read_height_map(tmp_path / "rgb.png", dx=1e-6, height_scale=1e-9)
    (tmp_path / "m.xyz").write_text("1 2 3")
    with pytest.raises(surfaces.InputError, match="unknown height-map format"):
        surfaces.read_height_map(tmp_path / "m.xyz", dx=1e-6)
    with pytest.raises(surfaces.InputError, match="NaN"):
        surfaces.HeightMap(np.full((4, 4), np.nan), dx=1.0)


def test_height_map_rows_columns_detrend():
    y, x = np.mgrid[0:32, 0:64] * 1e-6
    hm = surfaces.HeightMap(1e-3 * x + 2e-3 * y + 5e-7, dx=1e-6)
    assert len(hm.rows()) == 32 and len(hm.columns()) == 64
    assert np.max(np.abs(hm.detrend("plane").z)) < 1e-15
    assert hm.size == pytest.approx((64e-6, 32e-6))


# ---------------------------------------------------------------------- MPD rules (ISO 13473-1)


def test_mpd_of_a_cosine_is_its_amplitude():
    """Closed form: sampled at the 0.5 mm MPD spacing with crests on samples, every half segment of
    A cos(2 pi x / 10 mm) peaks at A; the mean and the regression slope of whole periods vanish, so
    MSD = A times the gain of the 2.4 mm low-pass applied forward and backward, 1/(1 + (2.4/10)^4)."""
    x = np.arange(0, 0.5, 0.5e-3)
    A = 1e-3
    res = surfaces.mpd(surfaces.profiles_from_array(A * np.cos(2 * np.pi * x / 10e-3), x=x))
    assert res.valid.all() and res.valid.size == 5
    assert res.mpd == pytest.approx(A / (1 + 0.24**4), rel=5e-3)
    assert res.etd == pytest.approx(0.2e-3 + 0.8 * res.mpd)


def test_mpd_validity_rules():
    x = np.arange(0, 0.5, 0.05e-3)
    z = 1e-3 * np.sin(2 * np.pi * x / 10e-3) + 2e-4 * np.sin(2 * np.pi * x / 3.7e-3)
    z[(x > 0.2) & (x < 0.22)] = np.nan                  # 20 % dropouts in segment 3 -> invalid
    cell = np.ceil(x / 0.5e-3 - 1e-9)                    # the 0.5 mm resampling cells
    spiky = (x > 0.3) & (x < 0.4) & (cell % 10 == 0)
    z[spiky] += 5e-3                                      # 5 mm steps over 0.5 mm (> 6 x 0.5 mm): spikes
    res = surfaces.mpd(surfaces.profiles_from_array(z, x=x))
    assert res.valid.tolist() == [True, True, False, False, True]
    assert res.dropout_ratio[2] == pytest.approx(0.2, abs=0.01)
    assert res.spike_ratio[3] > 0.05
    assert res.mpd == pytest.approx(res.msd[res.valid].mean())
    assert res.is_valid  # half of the segments valid
    with pytest.warns(UserWarning, match="no valid segment"):
        bad = surfaces.mpd(surfaces.profiles_from_array(z, x=x), max_dropout_ratio=-1.0)
    assert math.isnan(bad.mpd) and not bad.is_valid


# ---------------------------------------------------------------------- block reader, flat profiles, reprs


def _reference_read(path):
    """Independent reading with the csv module: x and z columns, empty/NaN/NA cells as NaN."""
    import csv

    rows = [r for r in csv.reader(open(path)) if r and not r[0].startswith("#")]
    header, body = rows[0], rows[1:]
    return {name: np.array([float("nan") if r[j].strip() in ("", "NA", "na") else float(r[j]) for r in body])
            for j, name in enumerate(header) if name.startswith(("x_", "z"))}


@pytest.mark.parametrize("block", [40, 97, 1 << 23])
def test_block_reader_matches_a_line_by_line_reading(tmp_path, monkeypatch, block):
    """Blocks of any size (one line, a few lines, the whole file) give the same numbers, dropouts included."""
    from surfaces import io as sio

    monkeypatch.setattr(sio, "_BLOCK_CHARS", block)
    rng = np.random.default_rng(1)
    lines = ["x_mm,z1_um,z2_mm,note"]
    for i in range(300):
        z1 = "" if i % 37 == 5 else ("NA" if i % 53 == 7 else f"{rng.normal():.6f}")
        z2 = "NaN" if i % 41 == 3 else f"{rng.normal() * 1e-2:.6g}"
        lines.append(f"{i * 0.01:.4f},{z1},{z2},text {i}")
        if i == 150:
            lines.append("# a comment in the middle")
    path = _write(tmp_path / "p.csv", "\n".join(lines) + "\n")
    ps = surfaces.read_profiles(path)
    ref = _reference_read(path)
    np.testing.assert_array_equal(ps[0].x, ref["x_mm"] * 1e-3)
    np.testing.assert_array_equal(ps[0].z, ref["z1_um"] * 1e-6)
    np.testing.assert_array_equal(ps[1].z, ref["z2_mm"] * 1e-3)
    assert np.isnan(ps[0].z).sum() == np.isnan(ref["z1_um"]).sum() > 0


@pytest.mark.parametrize("block", [40, 1 << 23])
def test_block_reader_names_the_line_of_a_bad_cell_far_down(tmp_path, monkeypatch, block):
    from surfaces import io as sio

    monkeypatch.setattr(sio, "_BLOCK_CHARS", block)
    rows = [f"{i},{i % 7}" for i in range(500)]
    rows[417] = "417,oops"
    path = _write(tmp_path / "p.csv", "x_mm,z_mm\n" + "\n".join(rows) + "\n")
    with pytest.raises(surfaces.InputError, match=r"p\.csv, line 419, column z_mm: expected a number, got 'oops'"):
        surfaces.read_profiles(path)
    rows[417] = "416,1"
    rows[300] = "299"
    path.write_text("x_mm,z_mm\n" + "\n".join(rows) + "\n")
    with pytest.raises(surfaces.InputError, match=r"line 302: expected 2 fields"):
        surfaces.read_profiles(path)
    rows[300] = "300,1"
    path.write_text("x_mm,z_mm\n" + "\n".join(rows) + "\n")
    with pytest.raises(surfaces.InputError, match=r"line 419, column x_mm: x must be strictly increasing"):
        surfaces.read_profiles(path)


@pytest.mark.parametrize("z", [np.full(400, 2.5e-3), np.linspace(-1e-3, 1e-3, 400), np.zeros(400)])
def test_flat_profile_has_no_psd(z):
    """A constant (or straight) profile would give A/A0 = 1 and mu = 0 silently: refused, saying why."""
    ps = surfaces.profiles_from_array(z, dx=1e-5, source="flat.csv")
    with pytest.raises(surfaces.InputError, match=r"flat\.csv: no roughness.*A/A0 = 1\) and mu = 0"):
        ps.psd()


def test_one_flat_profile_among_rough_ones_is_warned_about():
    rng = np.random.default_rng(0)
    z = np.vstack([rng.normal(size=512) * 1e-5, np.full(512, 1e-3), rng.normal(size=512) * 1e-5])
    ps = surfaces.profiles_from_array(z, dx=1e-5)
    with pytest.warns(UserWarning, match="z2 have heights constant"):
        ps.psd()


def test_flat_height_map_has_no_psd():
    with pytest.raises(surfaces.InputError, match="no roughness"):
        surfaces.HeightMap(np.full((16, 16), 3e-4), dx=1e-4).psd()


def test_reprs_are_short_and_informative():
    rng = np.random.default_rng(0)
    ps = surfaces.profiles_from_array(rng.normal(size=(2, 5000)) * 1e-5, dx=1e-5, source="scan.csv")
    p1 = ps.psd()
    items = {"ProfileSet(2 profiles": ps, "Profile('z1', 5000 samples": ps[0], "PSD1D(": p1,
             "PSD(": surfaces.example_road().tabulate(), "SelfAffine(": surfaces.example_road(),
             "HeightMap(16 x 16": surfaces.HeightMap(rng.normal(size=(16, 16)) * 1e-5, dx=1e-4),
             "MPDResult(": surfaces.mpd(surfaces.profiles_from_array(rng.normal(size=8000) * 1e-4, dx=5e-5))}
    for start, obj in items.items():
        text = repr(obj)
        assert text.startswith(start) and len(text) < 300 and "array(" not in text and "\n" not in text, text
