"""Zarr archives: the same numbers and labels as NetCDF, written batch by batch into chunk
regions (here and on worker processes), resumed after the client is killed."""
from __future__ import annotations

import signal
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import zarr

import pipeline
from pipeline.errors import Interrupted, SweepError, said
from pipeline.execute.zarr_store import block_chunks
from tests.helpers import wait_until

PROJECT = Path(__file__).resolve().parents[3]
GRID = dict(gap=[0.10, 0.15, 0.20], n_bumpers=[4, 8, 16, 32], strain=[0.7, 0.8],
            baseline=True, unconstrained=True, quiet=True)


@pytest.fixture(scope="module")
def record():
    from pipeline.histories import segment
    from pipeline.records import load_record

    return segment(load_record("pacoima"), 8.0)


@pytest.fixture(scope="module")
def reference(record):
    return pipeline.sweep([record], **GRID)


def _assert_same(ds, reference):
    assert set(ds.data_vars) - {"batch_done", "batch_members_done"} == set(reference.data_vars)
    for name in reference.data_vars:
        np.testing.assert_array_equal(ds[name].values, reference[name].values, err_msg=name)
        assert ds[name].attrs["units"] == reference[name].attrs["units"]
    assert ds.attrs["engine_fingerprint"] == reference.attrs["engine_fingerprint"]


def test_chunks_are_contiguous_member_ranges():
    assert block_chunks((100, 100, 100), 4096) == (1, 40, 100)
    assert block_chunks((3, 4), 5) == (1, 4)
    assert block_chunks((7,), 4096) == (7,)
    assert block_chunks((), 4096) == ()


def test_store_equals_netcdf_here_and_on_workers(record, reference, tmp_path):
    here = pipeline.sweep([record], out=tmp_path / "here.zarr", batch_size=5, **GRID)
    _assert_same(here, reference)
    opened = xr.open_zarr(tmp_path / "here.zarr")  # plain xarray, nothing of ours
    assert opened.attrs["complete"] == 1 and opened.batch_done.values.tolist() == [1] * 8
    assert opened.peak_total_accel.encoding["chunks"] == (1, 1, 1, 4, 5)  # (1, 1, 4) members
    workers = pipeline.sweep([record], out=tmp_path / "workers.zarr", batch_size=5,
                             workers=2, **GRID)
    _assert_same(workers, reference)


def test_a_store_of_another_sweep_is_refused(record, tmp_path):
    pipeline.sweep([record], out=tmp_path / "a.zarr", gap=0.2, quiet=True)
    with pytest.raises(SweepError, match="holds another sweep") as refused:
        pipeline.sweep([record], out=tmp_path / "a.zarr", gap=0.3, quiet=True)
    assert "Give force=True to replace it, or another out" in str(refused.value)
    assert "Give --force to replace it, or another --out" in said(refused.value)


def test_resume_after_the_client_is_killed(record, reference, tmp_path):
    """SIGKILL the process writing the store once some batches are done: the store stays
    readable and unfinished; the same sweep again fills in only the rest."""
    store = tmp_path / "killed.zarr"
    script = tmp_path / "run.py"
    script.write_text(textwrap.dedent(f"""
        import pipeline
        from pipeline.histories import segment
        from pipeline.records import load_record
        rec = segment(load_record("pacoima"), 8.0)
        pipeline.sweep([rec], out={str(store)!r}, batch_size=1, dt=2e-4,
                       **{GRID!r})
    """))
    proc = subprocess.Popen([sys.executable, str(script)], cwd=PROJECT)
    def three_done():
        try:
            return int(zarr.open_group(str(store), mode="r")["batch_done"][:].sum()) >= 3
        except Exception:  # noqa: BLE001 - the template is still being written
            return False

    def running():
        assert proc.poll() is None, "finished before it could be killed"

    wait_until(three_done, "three batches done", check=running)
    proc.send_signal(signal.SIGKILL)
    proc.wait(timeout=10)
    group = zarr.open_group(str(store), mode="r")
    kept = int(group["batch_done"][:].sum())
    assert group.attrs["complete"] == 0 and 3 <= kept < group["batch_done"].shape[0]
    # another batch size: the store's own chunks decide the batches
    resumed = pipeline.sweep([record], out=store, batch_size=7, dt=2e-4, **GRID)
    direct = pipeline.sweep([record], dt=2e-4, **GRID)
    _assert_same(resumed, direct)
    assert resumed.attrs["complete"] == 1


def test_a_batch_is_kept_a_part_at_a_time(record, reference, tmp_path, monkeypatch,
                                          count_simulated):
    """Issue 40: a Zarr store keeps a batch's work a part at a time (about KEEP_SECONDS of
    compute each), whatever the batch size. With the parts shrunk to the least (2 members,
    then 1), a run in one batch per block stopped in its third part (written, not yet
    counted) has kept the first two's 3 members in batch_members_done (no batch done);
    resumed, it runs only the other members and gives the NetCDF archive's numbers."""
    from pipeline.execute import batches, zarr_store

    monkeypatch.setattr(batches, "FIRST_PART", 2)
    monkeypatch.setattr(batches, "KEEP_SECONDS", 1e-12)
    real, written = zarr_store._write_rows, []

    def dying(*args):
        real(*args)
        written.append(1)
        if len(written) == 3:
            raise KeyboardInterrupt

    monkeypatch.setattr(zarr_store, "_write_rows", dying)
    store = tmp_path / "parts.zarr"
    with pytest.raises(Interrupted):
        pipeline.sweep([record], out=store, batch_size=100, **GRID)
    group = zarr.open_group(str(store), mode="r")
    assert group["batch_members_done"][:].tolist() == [3, 0, 0]
    assert group["batch_done"][:].tolist() == [0, 0, 0] and count_simulated == [2, 1, 1]
    monkeypatch.setattr(zarr_store, "_write_rows", real)
    count_simulated.clear()
    resumed = pipeline.sweep([record], out=store, batch_size=100, **GRID)
    assert sum(count_simulated) == 24 - 3 + 3 + 1 and max(count_simulated) <= 2
    _assert_same(resumed, reference)


def test_a_region_written_whole_but_not_marked_done_resumes(record, reference, tmp_path,
                                                            monkeypatch, count_simulated):
    """A run killed after a region's last part was counted in batch_members_done and before
    the region was marked done (a run of these tests hit it): the same sweep again marks it
    done without simulating it, simulates only the rest, and gives the NetCDF archive's
    numbers (its pace was a division by zero members)."""
    from pipeline.execute import zarr_store

    real, regions = zarr_store.write_batch, []

    def dying(*args, **keywords):
        place = args[6]
        if place.index == 1:
            raise KeyboardInterrupt
        regions.append(place.stop - place.start)
        return real(*args, **keywords)

    monkeypatch.setattr(zarr_store, "write_batch", dying)
    store = tmp_path / "unmarked.zarr"
    with pytest.raises(Interrupted):
        pipeline.sweep([record], out=store, batch_size=5, **GRID)
    group = zarr.open_group(str(store), mode="r+")
    assert group["batch_done"][0] == 1 and regions == [4]
    group["batch_done"][0] = 0  # as if killed between the two writes
    monkeypatch.setattr(zarr_store, "write_batch", real)
    count_simulated.clear()
    resumed = pipeline.sweep([record], out=store, batch_size=5, **GRID)
    # 24 bumper walls, 3 bare ones and the unconstrained building, less region 0's 4
    assert sum(count_simulated) == 28 - 4 and 0 not in count_simulated
    assert resumed.batch_done.values.tolist() == [1] * 8
    _assert_same(resumed, reference)


def test_command_line_writes_a_store(tmp_path):
    from studies import sweep as sweep_cli

    argv = ["--records", "pacoima", "--gap-cm", "20", "25", "--dt", "1e-3", "--quiet"]
    assert sweep_cli.main([*argv, "--out", str(tmp_path / "cli.zarr")]) == 0
    assert sweep_cli.main([*argv, "--out", str(tmp_path / "cli.nc")]) == 0
    with xr.open_zarr(tmp_path / "cli.zarr") as z, xr.open_dataset(tmp_path / "cli.nc") as n:
        np.testing.assert_array_equal(z.peak_total_accel.values, n.peak_total_accel.values)
        assert z.attrs["complete"] == 1
