"""The study pipeline: grids -> batched, parallel engine runs -> labelled Dataset -> NetCDF.

Short synthetic records (8 s) and a coarse, stable dt keep every sweep to about a second.
"""
import io
import os
import signal
import subprocess
import sys
import textwrap
import warnings
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import pipeline
from pipeline import progress as progress_module
from pipeline.errors import SweepError
from pipeline.execute import batches as batches_module
from pipeline.execute import netcdf_store
from pipeline.records import Record
from tests.helpers import assert_udunits

PROJECT = Path(__file__).resolve().parents[2]
DT = 0.004  # s: stable for every law used here, 4x coarser than needed for accuracy
GAPS = [0.06, 0.10, 0.14]  # m
N_BUMPERS = [4, 8]
SMALL = {"gap": GAPS, "n_bumpers": N_BUMPERS, "thickness": 0.03, "dt": DT}


def synthetic(name: str, period: float, amplitude: float, phase: float) -> Record:
    """8 s of a sine of `period` s and `amplitude` m/s^2 under a sin^2 envelope."""
    dt = 0.01
    t = np.arange(0.0, 8.0, dt)
    accel = amplitude * np.sin(np.pi * t / t[-1]) ** 2 * np.sin(2 * np.pi * t / period + phase)
    return Record(name=name, rsn=None, event="synthetic", station="", component="", dt=dt,
                  accel=accel, source=f"tests: synthetic {period} s pulse")


RECORDS = [synthetic("pulse-a", 1.5, 4.0, 0.0), synthetic("pulse-b", 1.0, 6.0, 0.5)]


@pytest.fixture(scope="module")
def reference():
    """The small sweep, run in this process in one batch per record."""
    return pipeline.sweep(RECORDS, **SMALL, workers=1, baseline=True, unconstrained=True,
                          quiet=True)


def assert_same_archive(a: xr.Dataset, b: xr.Dataset):
    """Identical values, coordinates and attributes, bar the creation time."""
    a, b = a.copy(), b.copy()
    for ds in (a, b):
        ds.attrs.pop("date_created")
    xr.testing.assert_identical(a, b)


# --------------------------------------------------------------------------- labels and files


def test_small_sweep_dims_coords_units(reference, tmp_path):
    ds = reference
    assert dict(ds.sizes) == {"record": 2, "gap": 3, "n_bumpers": 2, "floor": 5, "story": 4}
    assert list(ds.record.values) == ["pulse-a", "pulse-b"]
    np.testing.assert_array_equal(ds.floor, np.arange(5))
    np.testing.assert_array_equal(ds.story, np.arange(1, 5))
    np.testing.assert_array_equal(ds.gap, GAPS)
    # Fixed parameters are scalar coordinates.
    for name, value in {"thickness": 0.03, "strain": 0.8, "wall_k": 1.5e9, "cor": 0.45}.items():
        assert ds[name].dims == () and ds[name].item() == value
    expected = {
        "peak_total_accel": ("record", "gap", "n_bumpers", "floor"),
        "peak_interstory_drift": ("record", "gap", "n_bumpers", "story"),
        "peak_isolator_disp": ("record", "gap", "n_bumpers"),
        "max_indentation": ("record", "gap", "n_bumpers"),
        "max_impact_force": ("record", "gap", "n_bumpers"),
        "n_impacts": ("record", "gap", "n_bumpers"),
        "baseline_peak_total_accel": ("record", "gap", "floor"),
        "baseline_peak_interstory_drift": ("record", "gap", "story"),
        "amplification_total_accel": ("record", "gap", "n_bumpers", "floor"),
        "amplification_interstory_drift": ("record", "gap", "n_bumpers", "story"),
        "unconstrained_peak_isolator_disp": ("record",),
        "unconstrained_peak_total_accel": ("record", "floor"),
    }
    for name, dims in expected.items():
        assert ds[name].dims == dims, name
    assert ds.peak_total_accel.attrs["units"] == "m s-2"
    assert ds.peak_interstory_drift.attrs["units"] == "m"
    assert ds.max_impact_force.attrs["units"] == "N"
    assert ds.gap.attrs["units"] == "m" and ds.wall_k.attrs["units"] == "N m-1"
    for name, var in ds.variables.items():  # text takes no units (docs/archives.md)
        assert var.attrs.get("long_name") and (
            bool(var.attrs.get("units")) == (var.dtype.kind not in "OSU")), name
    assert_udunits(ds)
    # The sweep really pounds, and the ratios are what they say.
    assert ds.n_impacts.min() > 0 and ds.baseline_n_impacts.min() > 0
    assert (ds.unconstrained_peak_isolator_disp > max(GAPS)).all()
    xr.testing.assert_equal(ds.amplification_total_accel,
                            ds.peak_total_accel / ds.baseline_peak_total_accel)
    # Provenance.
    for key in ("project_version", "git_commit", "date_created", "dt", "impact_law",
                "building_masses", "damping_decision", "cor_decision", "m_eff",
                "record_pulse_a_source", "records", "impact_law_defaults"):
        assert key in ds.attrs, key
    assert ds.attrs["dt"] == DT

    out = tmp_path / "small.nc"
    from pipeline.archive import write_netcdf

    write_netcdf(ds, out)
    with xr.open_dataset(out) as back:
        back.load()
    xr.testing.assert_identical(back, ds)
    assert back.record.dtype.kind == "U" and "stacked" not in str(back.indexes)
    with xr.open_dataset(out) as raw:  # compressed with zlib on disk
        assert raw.peak_total_accel.encoding.get("zlib") is True


def test_unconstrained_peaks_helper(reference):
    ds = pipeline.unconstrained_peaks(RECORDS, dt=DT)
    assert ds.peak_isolator_disp.dims == ("record",)
    assert ds.peak_total_accel.dims == ("record", "floor")
    np.testing.assert_array_equal(ds.peak_isolator_disp,
                                  reference.unconstrained_peak_isolator_disp)
    assert (ds.n_impacts == 0).all()


@pytest.mark.parametrize("impact, wall_k, units", [("linear", None, "N m-1"),
                                                     ("jankowski", 2.75e9, "N m^(-1.5)"),
                                                     ("hertzdamp", 2.75e9, "N m^(-1.5)")])
def test_other_impact_laws(impact, wall_k, units):
    ds = pipeline.sweep(RECORDS[:1], gap=[0.06, 0.10], wall_k=wall_k, cor=[0.5, 0.8],
                        impact=impact, dt=DT, workers=0, quiet=True)
    assert ds.peak_isolator_disp.dims == ("record", "gap", "cor")
    assert "thickness" not in ds.coords and "n_bumpers" not in ds.coords
    assert ds.wall_k.attrs["units"] == units and ds.attrs["impact_law"] == impact
    assert_udunits(ds)
    assert ds.n_impacts.min() > 0


# --------------------------------------------------------------------------- bitwise identity


@pytest.mark.parametrize("batch_size", [1, 7, 10_000])
def test_batch_size_does_not_change_results(reference, batch_size, count_simulated):
    ds = pipeline.sweep(RECORDS, **SMALL, workers=1, baseline=True, unconstrained=True,
                        batch_size=batch_size, quiet=True)
    assert_same_archive(ds, reference)
    members = 3 * 2 + 3 + 1  # grid + baseline per gap + unconstrained, per record
    assert max(count_simulated) == min(batch_size, members)
    assert sum(count_simulated) == 2 * members  # baseline computed once per (record, gap)


def test_workers_and_scheduler_do_not_change_results(reference, tmp_path):
    from distributed import LocalCluster

    two = pipeline.sweep(RECORDS, **SMALL, workers=2, baseline=True, unconstrained=True,
                         batch_size=3, quiet=True, out=tmp_path / "two.nc")
    assert_same_archive(two, reference)
    with LocalCluster(n_workers=1, threads_per_worker=1, dashboard_address=None) as cluster:
        remote = pipeline.sweep(RECORDS, **SMALL, scheduler=cluster.scheduler_address,
                                baseline=True, unconstrained=True, quiet=True)
    assert_same_archive(remote, reference)
    with xr.open_dataset(tmp_path / "two.nc") as back:
        assert_same_archive(back.load(), reference)


# --------------------------------------------------------------------------- resuming


class Killed(Exception):
    """Stands in for the process dying."""


def test_interrupted_sweep_resumes_with_only_the_rest(reference, tmp_path, monkeypatch,
                                                      count_simulated):
    out = tmp_path / "resume.nc"
    work = tmp_path / "resume.nc.work"
    kwargs = dict(**SMALL, workers=1, baseline=True, unconstrained=True, batch_size=2,
                  quiet=True, out=out)
    real_save = netcdf_store.WorkFolder.save
    saved = []

    def dying_save(self, *args):
        real_save(self, *args)
        saved.append(1)
        if len(saved) == 3:
            raise Killed

    monkeypatch.setattr(netcdf_store.WorkFolder, "save", dying_save)
    with pytest.raises(Killed):
        pipeline.sweep(RECORDS, **kwargs)
    assert not out.exists() and len(list(work.glob("*.npz"))) == 3
    monkeypatch.setattr(netcdf_store.WorkFolder, "save", real_save)

    count_simulated.clear()
    ds = pipeline.sweep(RECORDS, **kwargs)
    total = 2 * (6 + 3 + 1)
    assert sum(count_simulated) == total - 3 * 2  # three batches of two were kept
    assert len(count_simulated) == 7
    assert_same_archive(ds, reference)
    with xr.open_dataset(out) as back:
        assert_same_archive(back.load(), reference)
    assert not work.exists()  # removed once the archive is written


def test_changed_arguments_never_reuse_stale_results(tmp_path, monkeypatch, count_simulated):
    out = tmp_path / "stale.nc"
    real_save = netcdf_store.WorkFolder.save

    def dying_save(self, *args):
        real_save(self, *args)
        raise Killed

    monkeypatch.setattr(netcdf_store.WorkFolder, "save", dying_save)
    with pytest.raises(Killed):
        pipeline.sweep(RECORDS, **SMALL, workers=1, batch_size=6, quiet=True, out=out)
    monkeypatch.setattr(netcdf_store.WorkFolder, "save", real_save)
    count_simulated.clear()
    changed = {**SMALL, "thickness": 0.04}
    ds = pipeline.sweep(RECORDS, **changed, workers=1, batch_size=6, quiet=True, out=out)
    assert sum(count_simulated) == 12  # the first record's batch was not reused
    fresh = pipeline.sweep(RECORDS, **changed, workers=1, quiet=True)
    assert_same_archive(ds, fresh)


def test_damaged_work_file_is_recomputed(tmp_path, count_simulated):
    work = tmp_path / "w.nc.work"
    work.mkdir()
    (work / "0123.npz").write_bytes(b"PK\x03\x04 truncated")
    pipeline.sweep(RECORDS[:1], **SMALL, workers=1, quiet=True, out=tmp_path / "w.nc")
    assert sum(count_simulated) == 6


# --------------------------------------------------------------------------- atomic archive


def test_failed_write_leaves_no_archive(reference, tmp_path, monkeypatch):
    from pipeline import archive

    out = tmp_path / "fail.nc"
    real = xr.Dataset.to_netcdf

    def half_then_die(self, path, *args, **kwargs):
        real(self, path, *args, **kwargs)
        with open(path, "r+b") as f:  # a half-written file
            f.truncate(os.path.getsize(path) // 2)
        raise Killed

    monkeypatch.setattr(xr.Dataset, "to_netcdf", half_then_die)
    with pytest.raises(Killed):
        archive.write_netcdf(reference, out)
    assert list(tmp_path.iterdir()) == []  # neither the archive nor a temporary file


@pytest.mark.parametrize("existing", [False, True])
def test_killed_writer_never_leaves_a_partial_archive(reference, tmp_path, existing):
    """SIGKILL a writer process after its bytes are written but before the rename."""
    out = tmp_path / "killed.nc"
    src = tmp_path / "src.nc"
    from pipeline.archive import write_netcdf

    write_netcdf(reference, src)
    if existing:
        write_netcdf(reference.isel(gap=[0]), out)
    script = textwrap.dedent(f"""
        import os, signal
        import xarray as xr
        from pipeline import archive
        ds = xr.open_dataset({str(src)!r}).load()
        real = xr.Dataset.to_netcdf
        def write_then_die(self, path, *args, **kwargs):
            real(self, path, *args, **kwargs)
            os.kill(os.getpid(), signal.SIGKILL)
        xr.Dataset.to_netcdf = write_then_die
        archive.write_netcdf(ds, {str(out)!r})
    """)
    proc = subprocess.run([sys.executable, "-c", script], cwd=PROJECT, capture_output=True,
                          env={**os.environ, "PYTHONPATH": str(PROJECT)})
    assert proc.returncode == -signal.SIGKILL, proc.stderr.decode()
    if existing:
        with xr.open_dataset(out) as back:  # the old archive, whole
            assert back.sizes["gap"] == 1
    else:
        assert not out.exists()
    leftovers = list(tmp_path.glob(".killed.nc.*.tmp"))
    assert len(leftovers) == 1  # hidden, never under the archive's name
    write_netcdf(reference, out)  # the next successful write sweeps it away
    assert not leftovers[0].exists()


# --------------------------------------------------------------------------- bad input


def no_compute(monkeypatch):
    def fail(*args, **kwargs):
        raise AssertionError("simulated despite bad input")

    monkeypatch.setattr(batches_module, "simulate_batch", fail)


@pytest.mark.parametrize("change, match", [
    ({"gap": [0.1, -0.05]}, "gap"),
    ({"gap": 0.0}, "gap"),
    ({"thickness": 0.06}, "thickness"),
    ({"thickness": [0.03, 0.2]}, "thickness"),
    ({"strain": 0.0}, "strain"),
    ({"strain": [0.5, 1.2]}, "strain"),
    ({"cor": 0.0}, "cor"),
    ({"cor": 1.5}, "cor"),
    ({"wall_k": 0.0}, "wall_k"),
    ({"wall_k": -1e9}, "wall_k"),
    ({"n_bumpers": 0}, "n_bumpers"),
    ({"n_bumpers": [4, 2.5]}, "n_bumpers"),
    ({"dt": 0.05}, "dt"),
    ({"dt": -0.001}, "dt"),
    ({"impact": "elastic"}, "impact"),
    ({"impact": "linear"}, "thickness"),  # bumper-only parameter given to another law
    ({"impact": "jankowski", "thickness": None, "n_bumpers": None}, "wall_k"),  # required
    ({"impact": "linear", "thickness": None, "n_bumpers": None, "baseline": True}, "baseline"),
    ({"gap": [0.1, 0.1]}, "gap"),
    ({"records": ["no-such-record-anywhere"]}, "records"),
    ({"records": [RECORDS[0], RECORDS[0]]}, "records"),
    ({"workers": -1}, "workers"),
    ({"batch_size": 0}, "batch_size"),
])
def test_bad_input_fails_fast_naming_the_parameter(change, match, monkeypatch):
    no_compute(monkeypatch)
    kwargs = {"records": RECORDS, **SMALL, "workers": 1, "quiet": True, **change}
    with pytest.raises(SweepError, match=match):
        pipeline.sweep(**kwargs)


def test_unwritable_output_fails_fast(tmp_path, monkeypatch):
    no_compute(monkeypatch)
    blocker = tmp_path / "a-file"
    blocker.write_text("not a folder")
    with pytest.raises(SweepError, match="out"):
        pipeline.sweep(RECORDS, **SMALL, workers=1, quiet=True, out=blocker / "x.nc")
    with pytest.raises(SweepError, match="out"):
        pipeline.sweep(RECORDS, **SMALL, workers=1, quiet=True, out=tmp_path)


# --------------------------------------------------------------------------- command line


def write_at2(path: Path, rec: Record):
    """A small NGA-West2 style AT2 file (values in g)."""
    values = rec.accel / 9.81
    rows = [" ".join(f"{v: .7E}" for v in values[i:i + 5]) for i in range(0, values.size, 5)]
    path.write_text("PEER NGA STRONG MOTION DATABASE RECORD\nSynthetic, 1/1/2000, Test, 0\n"
                    "ACCELERATION TIME SERIES IN UNITS OF G\n"
                    f"NPTS= {values.size}, DT= {rec.dt:.4f} SEC\n" + "\n".join(rows) + "\n")


def test_cli_writes_archive_and_reports_errors_on_one_line(tmp_path, capsys):
    from studies.sweep import main

    at2 = tmp_path / "PULSE_A.AT2"
    write_at2(at2, RECORDS[0])
    out = tmp_path / "cli.nc"
    code = main(["--records", str(at2), "--gap-cm", "6", "10", "--thickness-cm", "3",
                 "--wall-k-kn-mm", "1500", "--dt", str(DT), "--workers", "1", "--quiet",
                 "--out", str(out)])
    assert code == 0, capsys.readouterr().err
    with xr.open_dataset(out) as ds:
        np.testing.assert_allclose(ds.gap, [0.06, 0.10])
        assert ds.thickness.item() == pytest.approx(0.03) and ds.wall_k.item() == 1.5e9
        assert list(ds.record.values) == ["PULSE_A"]
    capsys.readouterr()

    code = main(["--records", str(at2), "--gap", "0.05", "--thickness", "0.05",
                 "--out", str(tmp_path / "bad.nc")])
    err = capsys.readouterr().err
    assert code == 2 and err.startswith("error: thickness") and err.count("\n") == 1
    help_text = subprocess.run([sys.executable, "-m", "studies.sweep", "--help"], cwd=PROJECT,
                               capture_output=True, text=True).stdout
    for option in ("--gap-cm", "--wall-k-kn-mm", "--baseline", "--unconstrained", "--workers",
                   "--scheduler", "--quiet", "N/m"):
        assert option in help_text


def test_records_entry_point_stays_light():
    code = "import sys, pipeline, pipeline.records; " \
           "assert not {'dask', 'distributed', 'xarray'} & set(sys.modules), sys.modules.keys()"
    subprocess.run([sys.executable, "-c", code], cwd=PROJECT, check=True)


def test_progress_bar_shows_counts_and_time_left():
    stream = io.StringIO()
    progress = progress_module.Progress(total=10, done=2, stream=stream, delay=0.0)
    progress.advance(3)
    progress.close()
    text = stream.getvalue()
    assert " 50% done (5 of 10 simulations finished)" in text and "left" in text
    # a running batch's partial work moves the percentage, never the count of finished ones
    partial = io.StringIO()
    progress = progress_module.Progress(total=10, stream=partial, delay=0.0)
    progress.running("batch", 1.4)
    progress.close()
    assert " 14% done (0 of 10 simulations finished, others under way)" in partial.getvalue()
    # no time left is guessed before anything finished (the kernel may be compiling)
    assert "time left: once the first finishes" in partial.getvalue()
    assert "~" not in partial.getvalue()
    # a log file gets whole lines, never a carriage return
    assert "\r" not in text + partial.getvalue() and text.endswith("\n")
    quiet = io.StringIO()
    progress_module.Progress(total=10, quiet=True, stream=quiet, delay=0.0).close()
    assert quiet.getvalue() == ""


def test_paper_records_keep_their_provenance(paper_record):
    """Real records, truncated to 8 s around their peak, named by their paper keys."""
    import dataclasses

    recs = []
    for key in ("kobe", "pacoima"):
        rec = paper_record(key)
        n = int(8 / rec.dt)
        start = max(0, int(np.argmax(np.abs(rec.accel))) - n // 2)
        recs.append(dataclasses.replace(rec, accel=rec.accel[start:start + n]))
    ds = pipeline.sweep(recs, gap=0.15, dt=DT, workers=1, quiet=True)
    assert list(ds.record.values) == ["kobe", "pacoima"]
    assert ds.gap.dims == () and ds.peak_isolator_disp.dims == ("record",)
    assert ds.attrs["record_kobe_found_in"] == recs[0].found_in
    assert ds.attrs["record_kobe_note"] == recs[0].note


# --------------------------------------------------------------------------- stand-ins


class Computed(Exception):
    """Raised by a simulation that must not have started yet."""


def test_stand_in_is_announced_before_any_compute(monkeypatch, tmp_path, capsys):
    from pipeline.archive import record_coords
    from pipeline.records import paper as records_module
    from studies import sweep as sweep_cli

    monkeypatch.setattr(records_module, "_builtin_resource", lambda: tmp_path / "missing.nc")
    monkeypatch.delenv(records_module.RECORDS_DIR_ENV, raising=False)

    def computed(*args, **kwargs):
        raise Computed

    monkeypatch.setattr(batches_module, "simulate_batch", computed)
    with pytest.warns(records_module.StandInWarning, match="STAND-IN: Kobe"), \
            pytest.raises(Computed):
        pipeline.sweep(["kobe"], gap=0.3, workers=0, quiet=True)
    # The command line says it on one line, before computing.
    with pytest.raises(Computed):
        sweep_cli.main(["--records", "kobe", "--gap", "0.3", "--workers", "0", "--quiet",
                        "--out", str(tmp_path / "x.nc")])
    err = capsys.readouterr().err
    assert err.startswith("warning: STAND-IN: Kobe 1995") and "\n" in err
    # Silenced like any warning, and the archive's record coordinate names it a stand-in.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        warnings.simplefilter("ignore", records_module.StandInWarning)
        rec = records_module.paper_record("kobe")
    assert rec.found_in == "stand-in"
    found = record_coords([rec, RECORDS[0]], ["kobe", "own"])["record_found_in"]
    assert found.values.tolist() == ["stand-in", "given"]
