"""A sweep on the device backend (backend="cuda", --backend cuda): the same labelled archive
as on the compiled CPU kernel, to round-off; its arguments say which loop ran; a work folder of
one backend is never resumed by the other; and what the device cannot do is refused, in one
line, before any record is read. On numba's CUDA simulator in CI (tests/conftest.py)."""
import numpy as np
import pytest

import pipeline
from engine import Building, Torsion
from pipeline.errors import SweepError
from pipeline.histories import segment
from tests.pipeline.small_sweep import DT, RECORDS, no_compute

pytest.importorskip("numba.cuda")
GAPS = [0.05, 0.08]


@pytest.fixture(scope="module")
def short():
    """The first 2 s of the small sweep's records: the simulator runs each step in Python."""
    return [segment(rec, 2.0) for rec in RECORDS]


def test_the_device_sweep_is_the_cpu_sweep_to_round_off(short, tmp_path):
    device = pipeline.sweep(short, gap=GAPS, n_bumpers=[4, 8], thickness=0.03, dt=DT,
                            baseline=True, quiet=True, backend="cuda")
    cpu = pipeline.sweep(short, gap=GAPS, n_bumpers=[4, 8], thickness=0.03, dt=DT,
                         baseline=True, quiet=True)
    assert set(device.data_vars) == set(cpu.data_vars)
    for name, value in cpu.data_vars.items():
        np.testing.assert_allclose(device[name].values, value.values, rtol=1e-12,
                                   err_msg=name)
    assert (cpu.n_impacts > 0).any()
    assert '"backend": "cuda"' in device.attrs["sweep_arguments"]
    assert "backend" not in cpu.attrs["sweep_arguments"]


def test_a_work_folder_of_the_cpu_is_not_resumed_on_the_device(short, tmp_path):
    work = tmp_path / "work"
    pipeline.sweep(short[:1], gap=GAPS, thickness=0.03, dt=DT, work_dir=work, quiet=True)
    kept = sorted(p.name for p in work.iterdir())
    pipeline.sweep(short[:1], gap=GAPS, thickness=0.03, dt=DT, work_dir=work, quiet=True,
                   backend="cuda")
    assert len(sorted(p.name for p in work.iterdir())) == 2 * len(kept)  # its own batches


def test_local_workers_sharing_one_gpu_are_refused_before_compute(monkeypatch):
    no_compute(monkeypatch)
    with pytest.raises(SweepError, match="one process per GPU.*--resources GPU=1"):
        pipeline.sweep(RECORDS, gap=GAPS, thickness=0.03, dt=DT, workers=2, backend="cuda",
                       quiet=True)


def test_the_twisting_model_is_refused_with_the_backend_that_runs_it(monkeypatch):
    no_compute(monkeypatch)
    twisting = Building(torsion=Torsion(plan_size=(30.0, 30.0)))
    with pytest.raises(SweepError, match="backend 'cuda': the twisting model takes 'numba'"):
        pipeline.sweep(["kobe"], gap=GAPS, thickness=0.03, dt=DT, moat="rectangular",
                       building=twisting, backend="cuda", quiet=True)
