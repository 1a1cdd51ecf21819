"""AT2 files (pipeline/records/at2.py): every header layout read back, the real files, bad
headers, counts, values and units refused or converted. (The rest of the record layer: the
other files of this folder.)"""

import numpy as np
import pytest

from pipeline import records as R
from pipeline.records import G, RecordError
from tests.pipeline.records.at2_writer import NGA_HEAD, OLD_HEAD, at2_tokens, simple_at2, write_at2

# ------------------------------------------------------------------ round trip, every layout

LAYOUTS = {
    "nga-west2": (NGA_HEAD, "NPTS=   {n}, DT=   .0100 SEC,", 0.01, "\n", "   ", 5),
    "old-peer": (OLD_HEAD, "NPTS=  {n}, DT= .00500 SEC", 0.005, "\n", "", 5),
    "spaces-around-equals": (NGA_HEAD, "NPTS =   {n} , DT =   .020 SEC ,", 0.02, "\n", "    ", 5),
    "no-comma": (NGA_HEAD, "NPTS=   {n}  DT=   .0100 SEC,", 0.01, "\n", "", 5),
    "numbers-first": (OLD_HEAD, "{n} 0.0100 NPTS, DT", 0.01, "\n", "", 8),
    "crlf": (NGA_HEAD, "NPTS=   {n}, DT=   .0100 SEC,", 0.01, "\r\n", "      ", 5),
}


@pytest.mark.parametrize("layout", LAYOUTS)
def test_round_trip_every_header_layout(tmp_path, layout):
    head, count_line, dt, newline, trailing, per_line = LAYOUTS[layout]
    n = 1003  # not a multiple of the values per line: the last line is short
    text, values_g = at2_tokens(n, seed=len(layout))
    path = write_at2(tmp_path / f"{layout}.AT2", head, count_line.format(n=n), text, per_line,
                     newline, trailing)
    rec = R.read_at2(path)
    assert rec.npts == n and rec.dt == dt
    assert np.array_equal(rec.accel, values_g * G)
    assert rec.accel.dtype == np.float64 and not rec.accel.flags.writeable
    assert rec.pga == pytest.approx(np.abs(values_g).max() * G, rel=1e-15)
    assert rec.pga_g == pytest.approx(np.abs(values_g).max(), rel=1e-15)
    assert rec.duration == pytest.approx(n * dt)
    assert rec.source == str(path) and rec.name == layout
    station, component = ("KJMA", "000") if head is NGA_HEAD else ("SYLMAR-CONVERTER STA", "142")
    assert (rec.station, rec.component) == (station, component)


# ------------------------------------------------------------------ the real files

SHARED_FILES = [("RSN1106_KOBE_KJM000.AT2", 0.8342, 7500, 0.02),
                ("SCS142.AT2", 0.8972, 8000, 0.005),
                ("RSN77_SFERN_PUL164-hor1.AT2", 1.2190, 4172, 0.01)]


@pytest.mark.parametrize(("fname", "pga_g", "npts", "dt"), SHARED_FILES)
def test_shared_records(records_dir, fname, pga_g, npts, dt):
    rec = R.read_at2(records_dir / fname)
    assert rec.pga_g == pytest.approx(pga_g, abs=5e-5)
    assert (rec.npts, rec.dt) == (npts, dt)
    assert np.all(np.isfinite(rec.accel))


# ------------------------------------------------------------------ bad input


@pytest.mark.parametrize(("count_line", "message"), [
    ("DT=   .0100 SEC,", "line 4: no NPTS"),
    ("NPTS=   abc, DT=   .0100 SEC,", "line 4: NPTS must be a positive integer"),
    ("NPTS=   12.5, DT=   .0100 SEC,", "line 4: NPTS must be a positive integer"),
    ("NPTS=   0, DT=   .0100 SEC,", "line 4: NPTS must be a positive integer"),
    ("NPTS=   12,", "line 4: no DT"),
    ("NPTS=   12, DT=   x.y SEC,", "line 4: cannot read DT"),
    ("NPTS=   12, DT=   0.0 SEC,", "line 4: DT must be > 0"),
    ("NPTS=   12, DT=   -.0100 SEC,", "line 4: DT must be > 0"),
    ("12 -0.01 NPTS, DT", "line 4: DT must be > 0"),
    ("NPTS=   11, DT=   .0100 SEC,", "12 values after the header but NPTS = 11"),
    ("NPTS=   13, DT=   .0100 SEC,", "12 values after the header but NPTS = 13"),
])
def test_bad_header_or_count(tmp_path, count_line, message):
    path = simple_at2(tmp_path, count_line)
    with pytest.raises(RecordError, match=rf"bad\.AT2.*{message}"):
        R.read_at2(path)


@pytest.mark.parametrize(("token", "message"), [
    ("abc", "is not a number"), ("1.0E-02-2.0E-02", "is not a number"), ("1,5", "not a number"),
    ("NaN", "is not finite"), ("-inf", "is not finite"), ("1.0E+999", "is not finite"),
])
def test_bad_values_report_the_line(tmp_path, token, message):
    tokens = at2_tokens(12)[0]
    tokens[7] = token  # 5 values per line: value 7 sits on data line 2, file line 6
    path = simple_at2(tmp_path, tokens=tokens)
    with pytest.raises(RecordError, match=rf"bad\.AT2, line 6: value .* {message}"):
        R.read_at2(path)


def test_empty_and_headerless_files(tmp_path):
    for content in (b"", b"  \r\n\n  "):
        path = tmp_path / "empty.AT2"
        path.write_bytes(content)
        with pytest.raises(RecordError, match=r"empty\.AT2: file is empty"):
            R.read_at2(path)
    path = tmp_path / "nohead.AT2"
    path.write_text("\n".join(["title", "event", "units", *at2_tokens(10)[0]]) + "\n")
    with pytest.raises(RecordError, match=r"nohead\.AT2: no NPTS/DT header line.*line 4"):
        R.read_at2(path)
    with pytest.raises(RecordError, match=r"missing\.AT2: no such file"):
        R.read_at2(tmp_path / "missing.AT2")
    with pytest.raises(RecordError, match=r"missing\.AT2: no such file"):
        R.load_record(tmp_path / "missing.AT2")


@pytest.mark.parametrize(("line3", "message"), [
    ("VELOCITY TIME SERIES IN UNITS OF CM/S", "line 3: not an acceleration record"),
    ("DISPLACEMENT TIME SERIES IN UNITS OF CM", "line 3: not an acceleration record"),
    ("ACCELERATION TIME SERIES IN UNITS OF FT/S/S", "line 3: units 'FT/S/S' not understood"),
    ("ACCELERATION TIME SERIES IN UNITS OF CM/S", "line 3: units 'CM/S' not understood"),
    ("ACCELERATION TIME SERIES IN UNITS OF M", "line 3: units 'M' not understood"),
])
def test_other_quantities_and_units_are_refused(tmp_path, line3, message):
    path = simple_at2(tmp_path, head=(NGA_HEAD[0], NGA_HEAD[1], line3))
    with pytest.raises(RecordError, match=rf"bad\.AT2, {message}"):
        R.read_at2(path)


# Header spellings of the acceleration units and how a value in them becomes m/s^2.
UNIT_SPELLINGS = [
    ("ACCELERATION TIME SERIES IN UNITS OF G", lambda v: v * G),
    ("ACCELERATION TIME HISTORY IN UNITS OF G. FILTER POINTS: HP=0.1 LP=25", lambda v: v * G),
    ("ACCELERATION TIME SERIES IN UNITS OF CM/S^2", lambda v: v / 100),
    ("ACCELERATION TIME SERIES IN UNITS OF CM/S/S", lambda v: v / 100),
    ("ACCELERATION TIME SERIES IN UNITS OF CM/SEC/SEC", lambda v: v / 100),
    ("ACCELERATION TIME SERIES IN UNITS OF CM/S2, FILTERED", lambda v: v / 100),
    ("Acceleration in units of cm/sec**2", lambda v: v / 100),
    ("ACCELERATION TIME SERIES IN UNITS OF CM / S / S", lambda v: v / 100),
    ("ACCELERATION TIME SERIES IN UNITS OF GAL", lambda v: v / 100),
    ("ACCELERATION TIME SERIES IN UNITS OF M/S^2", lambda v: v),
    ("ACCELERATION TIME SERIES IN UNITS OF M/S/S.", lambda v: v),
    ("ACCELERATION TIME SERIES IN UNITS OF M/SEC/SEC", lambda v: v),
    ("ACCELERATION TIME SERIES IN UNITS OF M/S2", lambda v: v),
    ("ACCELERATION TIME SERIES IN UNITS OF MM/S^2", lambda v: v / 1000),
    ("ACCELERATION TIME SERIES IN UNITS OF MM/S/S", lambda v: v / 1000),
]


@pytest.mark.parametrize(("line3", "to_si"), UNIT_SPELLINGS, ids=[u[0] for u in UNIT_SPELLINGS])
def test_acceleration_units_are_converted(tmp_path, line3, to_si):
    text, values = at2_tokens(12, seed=3)
    rec = R.read_at2(simple_at2(tmp_path, tokens=text, head=(NGA_HEAD[0], NGA_HEAD[1], line3)))
    assert np.array_equal(rec.accel, to_si(values))
    # The same numbers as a file in g, scaled by the factor between the units.
    in_g = R.read_at2(simple_at2(tmp_path, tokens=text, name="g.AT2"))
    factor = to_si(1.0) / G
    assert rec.accel == pytest.approx(in_g.accel * factor, rel=1e-14, abs=0)
    assert rec.pga_g == pytest.approx(np.abs(values).max() * factor, rel=1e-15)


def test_gal_values_equal_g_values(tmp_path):
    """981 cm/s^2 is 1 g (G = 9.81 m/s^2): the two files give the same record."""
    head = (NGA_HEAD[0], NGA_HEAD[1], "ACCELERATION TIME SERIES IN UNITS OF CM/S/S")
    gal = R.read_at2(simple_at2(tmp_path, tokens=["981.0", "-490.5", "9.81"] * 4, head=head))
    g = R.read_at2(simple_at2(tmp_path, tokens=["1.0", "-0.5", "0.01"] * 4, name="g.AT2"))
    assert gal.accel == pytest.approx(g.accel, rel=1e-15, abs=0)
    assert gal.pga_g == pytest.approx(1.0, rel=1e-15)


def test_contradicting_units_lines_are_refused(tmp_path):
    head = ("PEER RECORD IN UNITS OF G", NGA_HEAD[1], "ACCELERATION IN UNITS OF CM/S/S")
    with pytest.raises(RecordError, match=r"bad\.AT2, line 3: units 'CM/S/S' contradict line 1"):
        R.read_at2(simple_at2(tmp_path, head=head))
