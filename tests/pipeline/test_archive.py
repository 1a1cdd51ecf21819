"""Archives written atomically (pipeline/archive.py's write_netcdf): a failed write leaves no
archive, a writer killed before the rename never leaves a partial one; a code such as
collapse_mode labelled as a CF flag variable; Ctrl-C held back while a write is made whole."""
import os
import signal
import subprocess
import sys
import textwrap
import threading
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import engine
import pipeline
from engine.results import COLLAPSE_MODES, MODE
from tests.pipeline.small_sweep import (
    DT,
    RECORDS,
    Killed,
)

PROJECT = Path(__file__).resolve().parents[2]


# --------------------------------------------------------------------------- atomic archive


def test_failed_write_leaves_no_archive(reference, tmp_path, monkeypatch):
    from pipeline import archive

    out = tmp_path / "fail.nc"
    real = xr.Dataset.to_netcdf

    def half_then_die(self, path, *args, **kwargs):
        real(self, path, *args, **kwargs)
        with open(path, "r+b") as f:  # a half-written file
            f.truncate(os.path.getsize(path) // 2)
        raise Killed

    monkeypatch.setattr(xr.Dataset, "to_netcdf", half_then_die)
    with pytest.raises(Killed):
        archive.write_netcdf(reference, out)
    assert list(tmp_path.iterdir()) == []  # neither the archive nor a temporary file


@pytest.mark.parametrize("existing", [False, True])
def test_killed_writer_never_leaves_a_partial_archive(reference, tmp_path, existing):
    """SIGKILL a writer process after its bytes are written but before the rename."""
    out = tmp_path / "killed.nc"
    src = tmp_path / "src.nc"
    from pipeline.archive import write_netcdf

    write_netcdf(reference, src)
    if existing:
        write_netcdf(reference.isel(gap=[0]), out)
    script = textwrap.dedent(f"""
        import os, signal
        import xarray as xr
        from pipeline import archive
        ds = xr.open_dataset({str(src)!r}).load()
        real = xr.Dataset.to_netcdf
        def write_then_die(self, path, *args, **kwargs):
            real(self, path, *args, **kwargs)
            os.kill(os.getpid(), signal.SIGKILL)
        xr.Dataset.to_netcdf = write_then_die
        archive.write_netcdf(ds, {str(out)!r})
    """)
    proc = subprocess.run([sys.executable, "-c", script], cwd=PROJECT, capture_output=True,
                          env={**os.environ, "PYTHONPATH": str(PROJECT)})
    assert proc.returncode == -signal.SIGKILL, proc.stderr.decode()
    if existing:
        with xr.open_dataset(out) as back:  # the old archive, whole
            assert back.sizes["gap"] == 1
    else:
        assert not out.exists()
    leftovers = list(tmp_path.glob(".killed.nc.*.tmp"))
    assert len(leftovers) == 1  # hidden, never under the archive's name
    write_netcdf(reference, out)  # the next successful write sweeps it away
    assert not leftovers[0].exists()


def test_ctrl_c_waits_for_the_block_even_when_another_thread_receives_it():
    """A Ctrl-C delivered to a thread other than the main one (the compiled kernel's worker
    threads leave SIGINT unblocked) takes effect after the held block, not inside it: a batch
    written is then always a batch counted. Holding it by the main thread's signal mask alone
    let it through inside the block."""
    from pipeline.writing import sigint_held

    worker, delivered = threading.Event(), threading.Event()

    def receive():  # a thread started before the block: SIGINT unblocked in it
        worker.wait()
        signal.pthread_kill(threading.get_ident(), signal.SIGINT)
        delivered.set()

    # Ctrl-C at Python's own handler, whatever this process was started with: a shell's
    # background job (CI's `... &`) starts with SIGINT ignored, and then no Ctrl-C raises
    default = signal.signal(signal.SIGINT, signal.default_int_handler)
    thread = threading.Thread(target=receive)
    thread.start()
    finished = False
    try:
        with pytest.raises(KeyboardInterrupt):
            with sigint_held():
                worker.set()
                delivered.wait()
                for _ in range(1000):  # bytecodes enough for Python to run a pending handler
                    os.getpid()
                finished = True
            # on a loaded machine the handler may still be pending as the block ends; it runs
            # here, after the block, as the handler the block restored (a Ctrl-C after it)
            for _ in range(1_000_000):
                os.getpid()
    finally:
        thread.join()
        signal.signal(signal.SIGINT, default)
    assert finished


def test_an_archive_names_how_each_run_collapsed():
    """A building whose isolators have a displacement capacity can collapse: its archive
    carries collapse_mode beside collapsed, a CF flag variable, 2 (isolator capacity) exactly
    where the run collapsed and 0 elsewhere; the paper's building carries neither."""
    building = engine.Building(isolator=engine.Isolator.bilinear(capacity=0.08))
    ds = pipeline.sweep(RECORDS, gap=[0.06, 0.5], thickness=0.03, n_bumpers=4, dt=DT,
                        building=building, workers=1, quiet=True)
    mode = ds["collapse_mode"]
    assert mode.attrs["flag_meanings"] == " ".join(COLLAPSE_MODES)
    assert list(mode.attrs["flag_values"]) == [0, 1, 2, 3]
    fell = ds["collapsed"].values.astype(bool)
    assert fell.any() and not fell.all()  # the far gap lets the isolator pass 8 cm
    assert np.all(mode.values[fell] == MODE.isolator_capacity) and np.all(mode.values[~fell] == 0)
    assert "capacity, 0.08 m" in ds.attrs["building_collapse_text"]
    # the studies label theirs with the same declaration (pipeline.archive's helpers)
    from pipeline.archive import collapse_mode_coords, collapse_mode_variable

    again = collapse_mode_variable(mode.dims, mode.values.astype(float))
    assert again.dtype == np.int8 and again.dims == mode.dims
    assert {k: str(v) for k, v in again.attrs.items()} \
        == {k: str(v) for k, v in mode.attrs.items()}
    assert collapse_mode_variable(("run",), [0], "mine").attrs["long_name"] == "mine"
    assert collapse_mode_coords()["mode"].values.tolist() == list(COLLAPSE_MODES[1:])

