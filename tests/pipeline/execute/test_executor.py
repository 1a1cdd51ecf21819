"""The executor (pipeline/execute/executor.py): worker processes and a dask scheduler change no
number of the small sweep."""

import xarray as xr

import pipeline
from tests.pipeline.small_sweep import (
    RECORDS,
    SMALL,
    assert_same_archive,
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
