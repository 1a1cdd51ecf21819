"""Text records (pipeline/records/text.py): two columns, comma separated, one column with dt,
and errors naming the file and line."""

import numpy as np
import pytest

from pipeline import records as R
from pipeline.records import G, RecordError
from tests.pipeline.records.at2_writer import at2_tokens

# ------------------------------------------------------------------ text files


def _write_text(path, rows, sep=" ", head=()):
    lines = [*head, *(sep.join(str(v) for v in row) for row in rows)]
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.mark.parametrize(("units", "to_si"), [
    ("g", lambda v: v * G), ("G", lambda v: v * G), ("m/s^2", lambda v: v),
    ("m/s2", lambda v: v), ("M/S/S", lambda v: v), ("m s-2", lambda v: v),
    ("cm/s^2", lambda v: v / 100), ("cm/sec/sec", lambda v: v / 100),
    ("gal", lambda v: v / 100), ("Gal", lambda v: v / 100), ("mm/s^2", lambda v: v / 1000),
])
def test_text_two_columns(tmp_path, units, to_si):
    _, values = at2_tokens(20, seed=4)
    times = np.arange(20) * 0.005
    path = _write_text(tmp_path / "two.txt", zip([f"{t:.3f}" for t in times], values, strict=True),
                       head=("# time s, acceleration", "", "   # indented comment"))
    rec = R.read_text(path, units)
    assert np.array_equal(rec.accel, to_si(values))
    assert rec.dt == 0.005 and rec.npts == 20 and rec.name == "two"
    assert rec.source == str(path) and rec.found_in is None
    if units.lower() != "g":
        assert rec.accel == pytest.approx(R.read_text(path, "g").accel * to_si(1.0) / G,
                                          rel=1e-14, abs=0)


def test_text_comma_separated_times_starting_anywhere(tmp_path):
    _, values = at2_tokens(50, seed=5)
    times = 12.5 + np.arange(50) * 0.02
    path = _write_text(tmp_path / "RSN99_rec.csv", zip(times, values, strict=True), sep=", ")
    rec = R.read_text(path, "m/s^2")
    assert rec.dt == 0.02 and rec.time[0] == 0.0 and rec.rsn == 99
    assert np.array_equal(rec.accel, values)
    assert R.read_text(path, "m/s^2", dt=0.02).dt == 0.02  # a dt that agrees is accepted
    path.write_text("0,1.0\n0.01,2.0\n0.02,-3.0\n")  # no spaces, no final comment
    assert np.array_equal(R.read_text(path, "g").accel, np.array([1.0, 2.0, -3.0]) * G)


def test_text_one_column_with_dt(tmp_path):
    _, values = at2_tokens(30, seed=6)
    path = _write_text(tmp_path / "one.dat", [[v] for v in values], head=("# cm/s^2",))
    rec = R.read_text(path, "cm/s^2", dt=0.01)
    assert rec.dt == 0.01 and rec.npts == 30
    assert np.array_equal(rec.accel, values / 100)
    assert rec.duration == pytest.approx(0.3)


@pytest.mark.parametrize(("content", "kwargs", "message"), [
    ("1.0\n2.0\n", {"units": "g"}, r"one\.txt: one column of accelerations needs the time "
                                     r"step: pass dt"),
    ("1.0\n2.0\n", {"units": "g", "dt": 0.0}, r"one\.txt: dt must be a positive"),
    ("1.0\n2.0\n", {"units": "g", "dt": "x"}, r"one\.txt: dt must be a number"),
    ("1.0\n2.0\n", {"units": "cm/s"}, r"one\.txt: units 'cm/s' not understood"),
    ("1.0\n2.0\n", {"units": None}, r"one\.txt: units are required"),
    ("1.0\n2.0\n", {"units": 9.81}, r"one\.txt: units 9\.81 not understood"),
    ("1.0\n2.0\n", {"units": "furlongs"}, r"one\.txt: units 'furlongs' not understood"),
    ("# only a comment\n\n", {"units": "g", "dt": 0.01}, r"one\.txt: no data"),
    ("0 1.0\n0.01 2.0\n0.02 3.0\n0.031 4.0\n0.04 5.0\n", {"units": "g"},
     r"one\.txt, line 4: irregular time step: t = 0\.031 s follows t = 0\.02 s"),
    ("# t a\n0 1.0\n0.01 2.0\n0.01 3.0\n0.03 4.0\n", {"units": "g"},
     r"one\.txt, line 4: irregular time step"),
    ("0 1.0\n-0.01 2.0\n", {"units": "g"}, r"one\.txt, line 2: the times do not increase"),
    ("1 1.0\n1 2.0\n1 3.0\n", {"units": "g"}, r"one\.txt, line 3: the times do not increase"),
    ("0 1.0\n0.02 2.0\n0.01 3.0\n0.03 4.0\n", {"units": "g"},
     r"one\.txt, line 2: irregular time step: t = 0\.02 s follows t = 0 s"),
    ("0 1.0\n0.01 2.0\n0.02 3.0\n", {"units": "g", "dt": 0.02},
     r"one\.txt: dt = 0\.02 s given, but the times step by 0\.01 s"),
    ("0 1.0\n", {"units": "g"}, r"one\.txt, line 1: one row of time and acceleration"),
    ("time,accel\n0,1.0\n", {"units": "g"}, r"one\.txt, line 1: value 'time' is not a number"),
    ("0 1.0\n0.01 abc\n", {"units": "g"}, r"one\.txt, line 2: value 'abc' is not a number"),
    ("0 1.0\n0.01 1.0E-02-2.0E-02\n", {"units": "g"}, r"line 2: value .* is not a number"),
    ("0 1.0\n\n0.01 nan\n", {"units": "g"}, r"one\.txt, line 3: value 'nan' is not finite"),
    ("0 1.0\n0.01 1e999\n", {"units": "g"}, r"one\.txt, line 2: value '1e999' is not finite"),
    ("0,,1.0\n", {"units": "g"}, r"one\.txt, line 1: an empty field is not a number"),
    ("0 1.0 2.0\n", {"units": "g"}, r"one\.txt, line 1: 3 columns; expected 1 or 2"),
    ("0 1.0\n# c\n0.01\n", {"units": "g"}, r"one\.txt, line 3: 1 columns; expected 2 "
                                              r"\(as on line 1\)"),
])
def test_text_errors_name_the_file_and_line(tmp_path, content, kwargs, message):
    path = tmp_path / "one.txt"
    path.write_text(content)
    with pytest.raises(RecordError, match=message):
        R.read_text(path, **kwargs)


def test_text_missing_file(tmp_path):
    with pytest.raises(RecordError, match=r"nothing\.txt: no such file"):
        R.read_text(tmp_path / "nothing.txt", "g", dt=0.01)
