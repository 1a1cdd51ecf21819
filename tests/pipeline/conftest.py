"""Fixtures of the pipeline's tests."""
import pytest

import pipeline
from pipeline.execute import batches as batches_module
from tests.pipeline.small_sweep import RECORDS, SMALL


@pytest.fixture
def count_simulated(monkeypatch):
    """Count batches and members simulated in this process: the sizes of the batches run."""
    calls = []
    real = batches_module.simulate_batch

    def counting(accel, accel_dt, rows, *args, **kwargs):
        calls.append(len(rows))
        return real(accel, accel_dt, rows, *args, **kwargs)

    monkeypatch.setattr(batches_module, "simulate_batch", counting)
    return calls


@pytest.fixture(scope="module")
def reference():
    """The small sweep (small_sweep.py), run in this process in one batch per record: what the
    sweeps run otherwise (in batches, on workers, resumed) must equal; once per module."""
    return pipeline.sweep(RECORDS, **SMALL, workers=1, baseline=True, unconstrained=True,
                          quiet=True)
