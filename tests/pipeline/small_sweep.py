"""The small sweep several of the pipeline's tests run: two short synthetic records (8 s) and a
coarse, stable dt keep it to about a second; archives compared bar their creation time."""
import numpy as np
import pytest
import xarray as xr

from pipeline.execute import batches as batches_module
from pipeline.records import Record

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


def assert_same_archive(a: xr.Dataset, b: xr.Dataset):
    """Identical values, coordinates and attributes, bar the creation time."""
    a, b = a.copy(), b.copy()
    for ds in (a, b):
        ds.attrs.pop("date_created")
    xr.testing.assert_identical(a, b)


class Killed(Exception):
    """Stands in for the process dying."""


def no_compute(monkeypatch):
    """Make any simulation fail the test: bad input must be refused before compute."""
    def fail(*args, **kwargs):
        raise AssertionError("simulated despite bad input")

    monkeypatch.setattr(batches_module, "simulate_batch", fail)


def killed_after_three_batches(monkeypatch, kwargs) -> None:
    """pipeline.sweep(RECORDS, **kwargs) killed once its third batch is kept."""
    import pipeline
    from pipeline.execute import netcdf_store

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
    monkeypatch.setattr(netcdf_store.WorkFolder, "save", real_save)
