"""Fixtures of the archive tools' tests: one small sweep archive, NetCDF and Zarr."""
import warnings

import numpy as np
import pytest
import xarray as xr

import pipeline
from pipeline.records import Record


def pulse(name: str, period: float, amplitude: float) -> Record:
    """6 s of a sine under a sin^2 envelope: a record that makes contact in a second."""
    dt = 0.01
    t = np.arange(0.0, 6.0, dt)
    accel = amplitude * np.sin(np.pi * t / t[-1]) ** 2 * np.sin(2 * np.pi * t / period)
    return Record(name=name, rsn=None, event="synthetic", station="", component="", dt=dt,
                  accel=accel, source="tests: synthetic pulse")


@pytest.fixture(scope="module")
def archive(tmp_path_factory):
    """A 2 gaps x 2 bumper counts sweep of one record, with both reference blocks, as the
    sweep writes it (NetCDF), and the same archive as a Zarr store."""
    folder = tmp_path_factory.mktemp("sweep")
    path = folder / "small.nc"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the coarse dt's plausibility warning
        pipeline.sweep([pulse("pulse-a", 1.5, 4.0)], gap=[0.06, 0.10], n_bumpers=[4, 8],
                       thickness=0.03, dt=0.004, baseline=True, unconstrained=True,
                       quiet=True, out=path)
    with xr.open_dataset(path) as ds:
        ds = ds.load()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # zarr's notes on its format's string types
        ds.to_zarr(folder / "small.zarr")
    return path, ds
