"""The NetCDF store's work folder (pipeline/execute/netcdf_store.py): an interrupted sweep
resumes with only the rest, changed arguments never reuse stale results, a damaged work file
is recomputed."""

import pytest
import xarray as xr

import pipeline
from pipeline.execute import netcdf_store
from tests.pipeline.small_sweep import (
    RECORDS,
    SMALL,
    Killed,
    assert_same_archive,
    killed_after_three_batches,
)

# --------------------------------------------------------------------------- resuming


def test_interrupted_sweep_resumes_with_only_the_rest(reference, tmp_path, monkeypatch,
                                                      count_simulated):
    out = tmp_path / "resume.nc"
    work = tmp_path / "resume.nc.work"
    kwargs = dict(**SMALL, workers=1, baseline=True, unconstrained=True, batch_size=2,
                  quiet=True, out=out)
    killed_after_three_batches(monkeypatch, kwargs)
    assert not out.exists() and len(list(work.glob("*.npz"))) == 3

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


def test_a_run_with_other_options_keeps_the_interrupted_runs_work(tmp_path, monkeypatch,
                                                                  count_simulated):
    """Issue 40: an interrupted sweep rerun with one option changed deleted the kept work. Now
    the changed run takes away only its own batch files, keeps the interrupted run's and says
    so in one warning; the first configuration, run again, resumes from them, and its end
    removes the folder."""
    from pipeline.errors import KeptWorkNotice

    out, work = tmp_path / "keep.nc", tmp_path / "keep.nc.work"
    first = dict(**SMALL, workers=1, batch_size=2, quiet=True, out=out)
    killed_after_three_batches(monkeypatch, first)
    kept = sorted(p.name for p in work.glob("*.npz"))
    assert len(kept) == 3  # 3 batches of 2: 6 of the 12 simulations

    with pytest.warns(KeptWorkNotice, match="keeps 6 finished simulations of another "
                                            "configuration"):
        pipeline.sweep(RECORDS, **{**first, "thickness": 0.04})
    assert sorted(p.name for p in work.glob("*.npz")) == kept  # its own gone, the first's kept

    count_simulated.clear()
    pipeline.sweep(RECORDS, **first, force=True)  # the archive holds the other run now
    assert sum(count_simulated) == 6  # only the rest
    assert not work.exists()


def test_a_finished_run_takes_out_the_files_whose_members_all_ran_under_their_context():
    """WorkFolder.finish's check (netcdf_store._Completed), on member records as bytes: a
    file goes when every member ran under its context in the sweeps completed, whichever of
    them; a member that did not, another context, or no completed sweep keeps it."""
    import numpy as np

    from pipeline.members import MEMBER_DTYPE

    members = np.zeros(6, dtype=MEMBER_DTYPE)
    members["gap"] = np.arange(6) * 0.01
    members["law"] = "bumper"
    ran = netcdf_store._Completed({"a": [members[:4], members[4:5]]})
    assert ran("a", members[:4])  # one sweep's members, whole
    assert ran("a", members[2:5])  # members of two sweeps under the context
    assert not ran("a", members[3:6])  # the last never ran
    assert not ran("b", members[:2])  # another context
    assert not netcdf_store._Completed({})("a", members[:1])
    changed = members[:1].copy()
    changed["gap"] = np.nextafter(changed["gap"], 1.0)  # a record differing in its last bit
    assert not ran("a", changed)


def test_a_batch_is_its_members_whether_a_view_or_a_copy():
    """netcdf_store.taken gives members[which] (a view for a run of consecutive indices, as a
    fresh grid's batches are), and a batch's key is the SHA-256 of its context and its member
    records' bytes, as work folders written by earlier versions were named: whether the
    members are a view, a copy or a strided column of records, the same key."""
    import hashlib

    import numpy as np

    from pipeline.execute.keys import batch_key
    from pipeline.members import MEMBER_DTYPE

    members = np.zeros(8, dtype=MEMBER_DTYPE)
    members["gap"] = 0.1 + np.arange(8) * 0.01
    members["law"] = "bumper"
    run, scattered = np.arange(2, 6), np.array([1, 4, 5])
    view = netcdf_store.taken(members, run)
    assert np.shares_memory(view, members)
    np.testing.assert_array_equal(view, members[run])
    np.testing.assert_array_equal(netcdf_store.taken(members, scattered), members[scattered])
    assert netcdf_store.taken(members, np.arange(0)).size == 0
    assert np.shares_memory(netcdf_store.taken(members, slice(2, 6)), members)
    assert netcdf_store.as_slice(run) == slice(2, 6)  # accept copies a batch's peaks in a block
    assert netcdf_store.as_slice(scattered) is scattered
    assert netcdf_store.as_slice(np.array([3, 2])).tolist() == [3, 2]  # not a run upwards
    expected = hashlib.sha256(b"context" + members[run].tobytes()).hexdigest()
    assert batch_key("context", view) == batch_key("context", members[run].copy()) == expected
    assert batch_key("context", members[::2]) == \
        hashlib.sha256(b"context" + members[::2].tobytes()).hexdigest()
