"""Finding a record by what it is called (pipeline/records/lookup.py): text files, close names
suggested, a missing records directory."""

import numpy as np
import pytest

from pipeline import records as R
from pipeline.records import G, RecordError
from tests.pipeline.records.at2_writer import at2_tokens, simple_at2

# ------------------------------------------------------------------ text files


def _write_text(path, rows, sep=" ", head=()):
    lines = [*head, *(sep.join(str(v) for v in row) for row in rows)]
    path.write_text("\n".join(lines) + "\n")
    return path


def test_load_record_reads_text_files(tmp_path, monkeypatch):
    _, values = at2_tokens(10, seed=7)
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
    at2 = simple_at2(tmp_path, name="ok.AT2")
    with pytest.raises(RecordError, match=r"ok\.AT2: an AT2 file states its own units"):
        R.load_record(at2, units="g")
    with pytest.raises(RecordError, match="units/dt apply to text files only"):
        R.load_record("pacoima", dt=0.01)


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


# ------------------------------------------------------------------ labels as given

def test_a_record_is_labelled_as_the_user_called_it():
    """Issue 40: RSN1106:000 was stored as kobe, so ds.sel(record="RSN1106:000") failed. A
    name or selector is the label as given (a scaled one with its factor as the record writes
    it); one record called two ways is still one record, refused naming both."""
    records, names = R.resolve_records(["RSN1106:000"])
    assert names == ["RSN1106:000"]
    assert R.resolve_records(records)[1] == names  # passed on as Records (a recipe's), kept
    assert R.resolve_records(["kobe", "sylmar_converter"])[1] == ["kobe", "sylmar_converter"]
    assert R.resolve_records(["RSN1106:000*2"])[1] == ["RSN1106:000*2.0"]
    with pytest.raises(RecordError, match=r"repeated \['kobe \(as kobe, RSN1106:000\)'\]"):
        R.resolve_records(["kobe", "RSN1106:000"])


def test_a_sweep_selects_the_record_by_the_label_given():
    import pipeline
    from pipeline.histories import segment

    ds = pipeline.sweep([segment(R.load_record("RSN1106:000"), 2.0)], gap=0.1, dt=0.002,
                        quiet=True)
    assert ds.record.values.tolist() == ["kobe"]  # a Record: its paper key (else its name)
    ds = pipeline.sweep(["RSN1106:000"], gap=0.1, dt=0.002, quiet=True)
    assert float(ds.sel(record="RSN1106:000").peak_isolator_disp) > 0
