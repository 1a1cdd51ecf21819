"""The user's own records (issue 30, pipeline/records/lookup.py): a folder of AT2 files pairs
by the RSN and component in the file names, by an explicit 'A+B', and answers
RSN<n>:<component> selectors. (The user's own building: test_building_file_own_data.py.)"""
from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from pipeline.records import RecordError
from pipeline.records.cli import main as records_cli
from pipeline.records.lookup import component_from_name, load_record
from pipeline.records.pair import load_pair

SHARED = Path("/work/shared/records")
needs_records = pytest.mark.skipif(not SHARED.is_dir(), reason="no shared AT2 files")


@pytest.fixture(autouse=True)
def no_records_dir_env(monkeypatch):
    monkeypatch.delenv("BUMPERS_RECORDS_DIR", raising=False)


# --------------------------------------------------------------------------- records folders


@pytest.fixture
def folder(tmp_path):
    """Two real AT2 files, renamed as the two components of a made-up RSN 9001."""
    shutil.copy(SHARED / "RSN1106_KOBE_KJM000.AT2", tmp_path / "RSN9001_X_000.AT2")
    shutil.copy(SHARED / "SCS142.AT2", tmp_path / "RSN9001_X_090.AT2")
    return tmp_path


def test_components_from_peer_names():
    assert component_from_name("RSN953_NORTHR_MUL009.AT2") == "009"
    assert component_from_name("RSN953_NORTHR_MUL279.AT2") == "279"
    assert component_from_name("RSN77_SFERN_PUL164-hor1.AT2") == "164"
    assert component_from_name("RSN1503_CHICHI_TCU065-E.AT2") == "E"
    assert component_from_name("RSN9001_X_090.AT2") == "090"
    assert component_from_name("RSN9001.AT2") is None


@needs_records
def test_folder_pairs_by_rsn_in_the_file_names(folder):
    x, y = load_pair("RSN9001", records_dir=folder)
    assert (x.name, y.name) == ("RSN9001_X_000", "RSN9001_X_090")  # resampled to one step
    assert (x.component, y.component) == ("000", "090")  # the names', not the headers'
    assert x.found_in == y.found_in == "records_dir" and x.npts == y.npts


@needs_records
def test_folder_pairs_whatever_header_line_2_says(folder):
    for path in folder.glob("*.AT2"):
        lines = path.read_text().split("\n")
        lines[1] = "my own record"
        path.write_text("\n".join(lines))
    x, y = load_pair("RSN9001", records_dir=folder)
    assert (x.component, y.component) == ("000", "090")


@needs_records
def test_explicit_pair_of_two_files(folder):
    x, y = load_pair("RSN9001_X_090.AT2+RSN9001_X_000.AT2", records_dir=folder)
    assert (x.name, y.name) == ("RSN9001_X_090", "RSN9001_X_000")  # x first, as given
    x2, _ = load_pair(f"{folder / 'RSN9001_X_000.AT2'}+{folder / 'RSN9001_X_090.AT2'}")
    assert x2.name == "RSN9001_X_000"


@needs_records
def test_selector_is_found_in_the_records_dir(folder):
    rec = load_record("RSN9001:000", records_dir=folder)
    assert Path(rec.source).name == "RSN9001_X_000.AT2" and rec.found_in == "records_dir"
    assert Path(load_record("RSN9001:90", records_dir=folder).source).name == \
        "RSN9001_X_090.AT2"
    with pytest.raises(RecordError, match="RSN9001:180: no such record in .* nor in the "
                                          "library.*expected: AT2 files named RSN<n>"):
        load_record("RSN9001:180", records_dir=folder)


@needs_records
@pytest.mark.parametrize("keep, rename", [
    (["RSN9001_X_000.AT2"], {}),  # one component only
    (["RSN9001_X_000.AT2"], {"RSN9001_X_000.AT2": "RSN9001.AT2"}),  # no component anywhere
])
def test_unpairable_folder_says_what_it_expects(folder, keep, rename):
    for path in folder.glob("*.AT2"):
        if path.name not in keep:
            path.unlink()
    for old, new in rename.items():
        lines = (folder / old).read_text().split("\n")
        lines[1] = "my own record"
        (folder / new).write_text("\n".join(lines))
        (folder / old).unlink()
    with pytest.raises(RecordError) as err:
        load_pair("RSN9001", records_dir=folder)
    message = str(err.value)
    assert "\n" not in message
    assert "expected: AT2 files named RSN<n>_<anything><component>.AT2" in message
    assert "RSN953_NORTHR_MUL009.AT2 + RSN953_NORTHR_MUL279.AT2" in message and "'A.AT2+B.AT2'" \
        in message


@needs_records
def test_show_command(folder, capsys):
    assert records_cli(["--records-dir", str(folder), "--show", "RSN9001", "RSN9001:090"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert len(out) == 3 and "x = RSN9001_X_000 (component 000" in out[0]
    assert records_cli(["--records-dir", str(folder), "--show", "RSN9002"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("error: RSN9002: no pair") \
        and "expected:" in err
