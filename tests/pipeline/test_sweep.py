"""pipeline.sweep: grids -> batched, parallel engine runs -> labelled Dataset -> NetCDF; its
labels and units, other laws, an unwritable output refused before compute, stand-ins
announced. The small sweep of tests/pipeline/small_sweep.py keeps every sweep to
about a second. (Its bad input: test_grid.py; its batches, executor and work folder:
tests/pipeline/execute/; the atomic archive: test_archive.py; real records' provenance:
test_provenance.py; its command: tests/studies/test_sweep.py.)
"""
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import pipeline
from pipeline.errors import SweepError
from pipeline.execute import batches as batches_module
from tests.helpers import assert_udunits
from tests.pipeline.small_sweep import (
    DT,
    GAPS,
    RECORDS,
    SMALL,
    no_compute,
)

PROJECT = Path(__file__).resolve().parents[2]


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


def test_unwritable_output_fails_fast(tmp_path, monkeypatch):
    no_compute(monkeypatch)
    blocker = tmp_path / "a-file"
    blocker.write_text("not a folder")
    with pytest.raises(SweepError, match="out"):
        pipeline.sweep(RECORDS, **SMALL, workers=1, quiet=True, out=blocker / "x.nc")
    with pytest.raises(SweepError, match="out"):
        pipeline.sweep(RECORDS, **SMALL, workers=1, quiet=True, out=tmp_path)


def test_records_entry_point_stays_light():
    code = "import sys, pipeline, pipeline.records; " \
           "assert not {'dask', 'distributed', 'xarray'} & set(sys.modules), sys.modules.keys()"
    subprocess.run([sys.executable, "-c", code], cwd=PROJECT, check=True)


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


def test_more_worker_processes_than_cores_are_announced(monkeypatch):
    """Issue 40: `--workers 64` on 2 cores started 64 processes without a word. Said in one
    warning before any compute (a run that goes on: more workers are slower, not wrong)."""
    import os

    from pipeline.errors import PlausibilityWarning

    monkeypatch.setattr(os, "cpu_count", lambda: 2)
    with pytest.warns(PlausibilityWarning, match="workers = 64 on a machine of 2 cores"), \
            pytest.raises(SweepError):  # stopped right after, by a record that is not there
        pipeline.sweep(["no-such-record"], gap=0.1, workers=64, quiet=True)
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        with pytest.raises(SweepError):
            pipeline.sweep(["no-such-record"], gap=0.1, workers=2, quiet=True)
