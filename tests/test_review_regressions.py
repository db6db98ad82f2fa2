"""Regression tests for defects found in review (slip / validation input handling).

Each test failed before its fix: bad or merely unusual input must give a clear InputError naming the argument,
row and column (docs/conventions.md, errors and bad input), and plausible measurement files must be read.
"""

import numpy as np
import pytest

import validation
from persson import slip as ps
from persson.errors import InputError as PerssonInputError
from validation import InputError, Measurements, read_measurements

HEADER = "slip,speed_m_s,T_C,pressure_Pa,mu\n"


# ---- validation.measurements --------------------------------------------------------------------------------
def test_rows_of_empty_cells_from_spreadsheets_are_blank_lines(tmp_path):
    # spreadsheet "save as CSV" writes formatted-but-empty rows as ",,,,"; they are blank lines, not data
    p = tmp_path / "m.csv"
    p.write_text(",,,,\n" + HEADER + "1,0.1,20,3e5,0.5\n0.1,1,20,3e5,0.6\n,,,,\r\n , , ,,\n", encoding="utf-8")
    m = read_measurements(p)
    assert m.n == 2
    assert np.array_equal(m.slip, [1.0, 0.1]) and np.array_equal(m.lines, [3, 4])


def test_from_arrays_text_in_a_numeric_argument_is_an_input_error():
    with pytest.raises(InputError, match=r"row 1, column 'speed'.*'fast'"):
        Measurements.from_arrays(slip=1.0, speed=["0.1", "fast"], temperature=20.0, pressure=3e5, mu=0.5)
    with pytest.raises(InputError, match=r"column 'mu_std'.*'n/a'"):
        Measurements.from_arrays(slip=1.0, speed=[0.1, 1.0], temperature=20.0, pressure=3e5, mu=0.5,
                                 mu_std=["0.01", "n/a"])


@pytest.mark.parametrize("extra", [dict(mu_std=[0.01, 0.02, 0.03]), dict(wet=[0, 1, 0]),
                                   dict(series=["a", "b", "c"])])
def test_from_arrays_optional_column_of_wrong_length_is_an_input_error(extra):
    name = next(iter(extra))
    with pytest.raises(InputError, match=name):
        Measurements.from_arrays(slip=1.0, speed=[0.1, 1.0], temperature=20.0, pressure=3e5, mu=0.5, **extra)


def test_from_arrays_wet_accepts_the_readers_words_and_names_the_bad_row():
    m = Measurements.from_arrays(slip=1.0, speed=[0.1, 1.0, 2.0], temperature=20.0, pressure=3e5, mu=0.5,
                                 wet=["yes", "False", "1"])
    assert m.wet.tolist() == [True, False, True]
    with pytest.raises(InputError, match=r"row 1, column 'wet'.*'maybe'"):
        Measurements.from_arrays(slip=1.0, speed=[0.1, 1.0], temperature=20.0, pressure=3e5, mu=0.5,
                                 wet=["no", "maybe"])


# ---- validation.predict -------------------------------------------------------------------------------------
def test_predict_with_something_that_is_not_a_model_is_an_input_error():
    m = Measurements.from_arrays(slip=1.0, speed=[0.1, 1.0], temperature=20.0, pressure=3e5, mu=0.5)
    with pytest.raises(InputError, match="persson.Model"):
        validation.predict(lambda v: 0.5 + 0.0 * v, m)


# ---- persson.slip -------------------------------------------------------------------------------------------
def test_slip_helpers_report_shapes_that_do_not_broadcast():
    c = ps.Contact(0.02, 0.01, 3e9, {"sakai_n": 4})
    with pytest.raises(PerssonInputError, match="slip, mu_local"):
        ps.brush_mu(c, [0.1, 0.2], [0.5, 0.6, 0.7], pressure=3e5)
    with pytest.raises(PerssonInputError, match="wheel_speed, disk_speed"):
        ps.drft_kinematics([1.0, 2.0], [3.0, 4.0, 5.0])
    with pytest.raises(PerssonInputError, match="slip, speed"):
        ps.drft_speeds([0.1, 0.2], [3.0, 4.0, 5.0])
    with pytest.raises(PerssonInputError, match="omega_wheel, omega_disk"):
        ps.drft_from_angular([1.0, 2.0], [3.0, 4.0, 5.0], wheel_radius=0.1, track_radius=0.2)
