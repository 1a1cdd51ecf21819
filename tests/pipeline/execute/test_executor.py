"""The executor (pipeline/execute/executor.py): worker processes, a dask scheduler and a batch
kept in parts change no number of the small sweep."""

import xarray as xr

import pipeline
from tests.pipeline.small_sweep import (
    RECORDS,
    SMALL,
    assert_same_archive,
    killed_after_three_batches,
)


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


def test_a_batch_is_kept_a_part_at_a_time_whatever_its_size(reference, tmp_path, monkeypatch,
                                                            count_simulated):
    """Issue 40: work is kept every KEEP_SECONDS of compute, not a batch at a time. With the
    parts shrunk to the least (a first part of 2 members, then 1), a run in one batch per
    record keeps its work part by part, killed after three parts it has kept 4 simulations,
    and resumed it computes only the rest and gives the reference's archive bit for bit."""
    from pipeline.execute import batches

    monkeypatch.setattr(batches, "FIRST_PART", 2)
    monkeypatch.setattr(batches, "KEEP_SECONDS", 1e-12)
    out, work = tmp_path / "parts.nc", tmp_path / "parts.nc.work"
    kwargs = dict(**SMALL, workers=1, batch_size=100, baseline=True, unconstrained=True,
                  quiet=True, out=out)
    killed_after_three_batches(monkeypatch, kwargs)
    assert count_simulated == [2, 1, 1] and len(list(work.glob("*.npz"))) == 3
    count_simulated.clear()
    ds = pipeline.sweep(RECORDS, **kwargs)
    assert count_simulated == [2] + [1] * (2 * (6 + 3 + 1) - 4 - 2)  # the rest, in parts
    assert_same_archive(ds, reference)


def test_on_dask_a_batch_is_kept_a_part_at_a_time(reference, tmp_path, monkeypatch):
    """Issue 40: on dask too, work is kept a part at a time (about KEEP_SECONDS of compute
    each, sized in the client from the parts' pace), not a batch at a time. With the parts
    shrunk to the least, a run in one batch per record stopped once three parts are kept has
    kept them (the parts in flight then are lost, no more); resumed, it runs only the rest,
    in parts, and gives the reference's archive bit for bit."""
    from distributed import Client, LocalCluster

    from pipeline.execute import batches, netcdf_store

    monkeypatch.setattr(batches, "FIRST_PART", 2)
    monkeypatch.setattr(batches, "KEEP_SECONDS", 1e-12)
    accepted, real_accept = [], netcdf_store.NetCDFStore.accept

    def accept(self, batch, peaks):  # in this process, the client, as each part completes
        accepted.append(batch.size)
        real_accept(self, batch, peaks)

    monkeypatch.setattr(netcdf_store.NetCDFStore, "accept", accept)
    out, work = tmp_path / "dask.nc", tmp_path / "dask.nc.work"
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        kwargs = dict(**SMALL, scheduler=client, batch_size=100, baseline=True,
                      unconstrained=True, quiet=True, out=out)
        killed_after_three_batches(monkeypatch, kwargs)
        assert len(list(work.glob("*.npz"))) == 3 and accepted == [2, 2, 1]
        accepted.clear()
        ds = pipeline.sweep(RECORDS, **kwargs)
    assert max(accepted) <= 2 and sum(accepted) == 2 * (6 + 3 + 1) - 5
    assert_same_archive(ds, reference)
