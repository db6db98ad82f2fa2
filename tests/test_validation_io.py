"""validation: reading measurements and case files; bad input names the file, row and column."""

import shutil
import warnings
from pathlib import Path

import numpy as np
import pytest

import validation
from validation import InputError, Measurements, UnitWarning, read_measurements

GOOD = """# a DRFT run
# comment lines start with #
slip,speed_m_s,T_C,pressure_Pa,mu,mu_std,wet,series
1,0.01,20,300000,0.61,0.01,0,run A
1,0.1,20,300000,0.72,0.012,0,run A
0.05,1.0,20,300000,0.55,0.02,1,"run B, wet"
"""


def _write(tmp_path, text, name="m.csv"):
    p = tmp_path / name
    p.write_text(text)
    return p


def test_reads_columns_comments_and_optional_columns(tmp_path):
    m = read_measurements(_write(tmp_path, GOOD))
    assert m.n == 3
    np.testing.assert_array_equal(m.slip, [1, 1, 0.05])
    np.testing.assert_array_equal(m.speed, [0.01, 0.1, 1.0])
    np.testing.assert_allclose(m.sliding_speed, [0.01, 0.1, 0.05])
    np.testing.assert_array_equal(m.mu_std, [0.01, 0.012, 0.02])
    assert m.wet.tolist() == [False, False, True]
    assert m.series == ("run A", "run A", "run B, wet")
    assert m.lines.tolist() == [4, 5, 6]
    assert m.has_slip_rows and m.is_sliding.tolist() == [True, True, False]
    with pytest.raises(ValueError):
        m.mu[0] = 1.0  # frozen arrays


def test_round_trip_through_to_csv(tmp_path):
    m = read_measurements(_write(tmp_path, GOOD))
    out = m.to_csv(tmp_path / "copy.csv", comments=("copied",))
    m2 = read_measurements(out)
    for a in ("slip", "speed", "temperature", "pressure", "mu", "mu_std", "wet"):
        np.testing.assert_array_equal(getattr(m2, a), getattr(m, a))
    assert m2.series == m.series


def test_optional_columns_absent(tmp_path):
    m = read_measurements(_write(tmp_path, "slip,speed_m_s,T_C,pressure_Pa,mu\n1,0.1,20,3e5,0.5\n"))
    assert m.mu_std is None and not m.wet.any() and m.series == ("",)


@pytest.mark.parametrize("text, words", [
    ("slip,speed_m_s,T_C,mu\n1,0.1,20,0.5\n", ["m.csv", "line 1", "'pressure_Pa'"]),
    ("slip,speed_m_s,T_C,pressure_Pa,mu\n1,0.1,20,3e5,0.5\n1,fast,20,3e5,0.5\n",
     ["m.csv", "line 3", "data row 2", "'speed_m_s'", "'fast'"]),
    ("slip,speed_m_s,T_C,pressure_Pa,mu\n1,0.1,20,3e5,0.5\n1,0.2,20,3e5,-0.1\n",
     ["m.csv", "line 3", "'mu'", ">= 0"]),
    ("# c\nslip,speed_m_s,T_C,pressure_Pa,mu\n1,0.1,20,3e5,0.5\n1.2,0.2,20,3e5,0.4\n",
     ["m.csv", "line 4", "'slip'", "(0, 1]"]),
    ("slip,speed_m_s,T_C,pressure_Pa,mu\n0,0.1,20,3e5,0.5\n", ["line 2", "'slip'"]),
    ("slip,speed_m_s,T_C,pressure_Pa,mu\n5,0.1,20,3e5,0.5\n100,0.1,20,3e5,0.6\n", ["'slip'", "percent"]),
    ("slip,speed_m_s,T_C,pressure_Pa,mu\n1,200,20,3e5,0.5\n", ["'speed_m_s'", "km/h"]),
    ("slip,speed_m_s,T_C,pressure_Pa,mu\n1,0.1,20,300,0.5\n1,0.1,20,500,0.5\n", ["'pressure_Pa'", "kPa"]),
    ("slip,speed_m_s,T_C,pressure_Pa,mu\n1,0.1,293,3e5,0.5\n1,0.1,313,3e5,0.5\n", ["'T_C'", "kelvin"]),
    ("slip,speed_m_s,T_C,pressure_Pa,mu,mu_std\n1,0.1,20,3e5,0.5,0.01\n1,0.2,20,3e5,0.5,\n", ["line 3", "'mu_std'"]),
    ("slip,speed_m_s,T_C,pressure_Pa,mu,wet\n1,0.1,20,3e5,0.5,maybe\n", ["line 2", "'wet'"]),
    ("slip,speed_m_s,T_C,pressure_Pa,mu\n1,0.1,20,3e5,\n", ["line 2", "'mu'", "empty"]),
    ("# only comments\n", ["m.csv", "header"]),
    ("slip,speed_m_s,T_C,pressure_Pa,mu\n", ["m.csv", "no data rows"]),
])
def test_bad_measurements_name_file_line_and_column(tmp_path, text, words):
    with pytest.raises(InputError) as exc:
        read_measurements(_write(tmp_path, text))
    msg = str(exc.value)
    for w in words:
        assert w in msg, (w, msg)
    assert isinstance(exc.value, ValueError)


def test_missing_file():
    with pytest.raises(InputError, match="nope.csv"):
        read_measurements("nope.csv")


@pytest.mark.parametrize("text, word", [
    ("slip,speed_m_s,T_C,pressure_Pa,mu\n1,60,20,3e5,0.5\n", "km/h"),
    ("slip,speed_m_s,T_C,pressure_Pa,mu\n1,0.1,20,3e5,0.5\n1,0.1,20,5e3,0.5\n", "Pa"),
    ("slip,speed_m_s,T_C,pressure_Pa,mu\n1,0.1,180,3e5,0.5\n", "deg C"),
])
def test_suspicious_units_warn(tmp_path, text, word):
    with pytest.warns(UnitWarning, match=word):
        read_measurements(_write(tmp_path, text))


def test_good_file_gives_no_warning(tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        read_measurements(_write(tmp_path, GOOD))


def test_from_arrays_checks_like_the_reader():
    m = Measurements.from_arrays(slip=1.0, speed=[0.1, 1.0], temperature=20.0, pressure=3e5, mu=[0.5, 0.6])
    assert m.n == 2 and m.source == "<arrays>"
    with pytest.raises(InputError, match="slip"):
        Measurements.from_arrays(slip=[0.5, 1.5], speed=1.0, temperature=20.0, pressure=3e5, mu=0.5)
    with pytest.raises(InputError, match="mu"):
        Measurements.from_arrays(slip=1.0, speed=1.0, temperature=20.0, pressure=3e5, mu=np.nan)


# ---- case files ----------------------------------------------------------------------------------------------
def _copy_case(tmp_path, name="null"):
    src = Path(validation.case_path(name)).parent
    dst = tmp_path / name
    shutil.copytree(src, dst)
    return dst


def test_load_shipped_case():
    case = validation.load_case("null")
    assert case.name == "null" and case.measurements.n > 50
    assert case.model.effect_names == ("adhesion",)
    assert case.contact is not None and case.contact.length == pytest.approx(0.02)
    assert case.measurements.has_slip_rows and case.measurements.wet.any()
    assert validation.load_case(case.path).name == "null"  # by path too
    assert {"example", "null", "hidden_flash", "hidden_adhesion", "hidden_microtexture",
            "hidden_strain_softening"} <= set(validation.shipped_cases())


def test_case_pointing_at_missing_measurements_names_the_file(tmp_path):
    d = _copy_case(tmp_path)
    (d / "measurements.csv").unlink()
    with pytest.raises(InputError) as exc:
        validation.load_case(d / "case.toml")
    assert "measurements.csv" in str(exc.value) and "case.toml" in str(exc.value)


def test_case_pointing_at_missing_psd_names_the_file(tmp_path):
    d = _copy_case(tmp_path)
    (d / "surface_psd.csv").unlink()
    with pytest.raises(InputError) as exc:
        validation.load_case(d)
    assert "surface_psd.csv" in str(exc.value)


def test_case_with_bad_measurement_row(tmp_path):
    d = _copy_case(tmp_path)
    lines = (d / "measurements.csv").read_text().splitlines()
    i = next(k for k, ln in enumerate(lines) if not ln.startswith("#")) + 3  # third data row
    cells = lines[i].split(",")
    cells[4] = "n/a"
    lines[i] = ",".join(cells)
    (d / "measurements.csv").write_text("\n".join(lines) + "\n")
    with pytest.raises(InputError) as exc:
        validation.load_case(d)
    msg = str(exc.value)
    assert "measurements.csv" in msg and f"line {i + 1}" in msg and "'mu'" in msg


def test_slip_rows_need_a_contact(tmp_path):
    d = _copy_case(tmp_path)
    text = (d / "case.toml").read_text()
    start = text.index("[contact]")
    end = text.index("[model]")
    (d / "case.toml").write_text(text[:start] + text[end:])
    with pytest.raises(InputError, match="contact"):
        validation.load_case(d)


def test_fit_names_are_checked(tmp_path):
    d = _copy_case(tmp_path)
    text = (d / "case.toml").read_text().replace('effects = ["adhesion"]',
                                                 'effects = ["adhesion"]\nfit = ["adhesion.nonsense"]')
    (d / "case.toml").write_text(text)
    with pytest.raises(InputError, match="nonsense"):
        validation.load_case(d)


def test_duplicated_rows_are_flagged_naming_the_lines(tmp_path):
    from validation.measurements import DuplicateRowsWarning

    text = GOOD + "1,0.1,20,300000,0.72,0.012,0,run A\n0.05,1.0,20,300000,0.55,0.02,1,\"run B, wet\"\n"
    with pytest.warns(DuplicateRowsWarning) as rec:
        m = read_measurements(_write(tmp_path, text))
    msg = str(rec[0].message)
    assert m.n == 5 and "2 row(s) repeat" in msg and "line 7 = line 5" in msg and "line 8 = line 6" in msg
    # same conditions with another mu, or another pressure, are data, not duplicates
    with warnings.catch_warnings():
        warnings.simplefilter("error", DuplicateRowsWarning)
        read_measurements(_write(tmp_path, GOOD + "1,0.1,20,300000,0.73,0.012,0,run A\n"
                                                  "1,0.1,20,310000,0.72,0.012,0,run A\n"))


def test_measurements_repr_is_one_line():
    m = Measurements.from_arrays(slip=1.0, speed=[0.01, 0.1, 1.0], temperature=20.0, pressure=3e5,
                                 mu=[0.5, 0.6, 0.7])
    text = repr(m)
    assert text.startswith("Measurements(3 rows") and "array(" not in text and "\n" not in text


def test_q1_equal_to_the_last_q_of_the_psd_within_rounding_is_accepted(tmp_path):
    """q1 written with 6 digits against a PSD table written with 10: the same wavevector (relative tolerance 1e-6);
    a q1 really past the table is refused with enough digits to show the difference."""
    d = _copy_case(tmp_path)
    psd = d / "surface_psd.csv"
    lines = psd.read_text().splitlines()
    q_last, c_last = lines[-1].split(",")
    lines[-1] = f"2737169.534,{c_last}"          # the table ends at 2.737169534e6 rad/m
    psd.write_text("\n".join(lines) + "\n")
    toml = (d / "case.toml").read_text()
    (d / "case.toml").write_text(toml.replace('psd = "surface_psd.csv"', 'psd = "surface_psd.csv"\nq1 = 2.73717e+06'))
    case = validation.load_case(d)
    # 2.73717e6 is 1.7e-7 past the table's end: the table's own last q is used
    assert case.model.surface.q_range[1] == pytest.approx(2737169.534, rel=1e-12)
    (d / "case.toml").write_text(toml.replace('psd = "surface_psd.csv"', 'psd = "surface_psd.csv"\nq1 = 2.7375e+06'))
    with pytest.raises(InputError) as exc:
        validation.load_case(d)
    msg = str(exc.value)
    assert "q1 = 2737500 rad/m" in msg and "last q = 2737169.534 rad/m" in msg and "case.toml" in msg
