"""Fixtures of the pipeline's tests."""
import pytest

from pipeline.execute import batches as batches_module


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
