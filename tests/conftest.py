"""Shared fixtures: the paper's records as the record layer resolves them, and the backend
every engine test runs on. Helpers that are not fixtures are in tests/helpers.py.

The device loops' tests (backend "cuda") run on numba's CUDA simulator unless the environment
says otherwise: NUMBA_ENABLE_CUDASIM=0 runs them on a GPU. numba reads it when first imported,
hence here, before any test module imports it."""
import os
import sys
from pathlib import Path

import pytest

os.environ.setdefault("NUMBA_ENABLE_CUDASIM", "1")

# Bytecode written and read back, whatever the environment says (PYTHONDONTWRITEBYTECODE): the
# suite runs in some sixty processes (pytest-xdist's workers, the kernels' warm-up, the commands
# and examples it runs), and without .pyc files each compiles every module it imports from source
# (measured on a fresh clone, 2 cores: collection alone 9.0 s of CPU a process against 4.1 s).
# Set here, before pytest imports the test modules and starts its workers, which inherit it.
sys.dont_write_bytecode = False
os.environ.pop("PYTHONDONTWRITEBYTECODE", None)

from tests.helpers import SHARED_RECORDS  # noqa: E402  (after the environment above)


@pytest.fixture(scope="session")
def records_dir() -> Path:
    """../shared/records: real AT2 files the project must read in place, never copy."""
    if not SHARED_RECORDS.is_dir():
        pytest.skip("../shared/records is not present")
    return SHARED_RECORDS


@pytest.fixture(scope="session")
def records_dir_args() -> list[str]:
    """Command-line arguments pointing a recipe at ../shared/records when it is there."""
    return ["--records-dir", str(SHARED_RECORDS)] if SHARED_RECORDS.is_dir() else []


@pytest.fixture(scope="session")
def paper_record():
    """Load one of the paper's records by key: from ../shared/records when it is there, else
    built in (Kobe, Sylmar Converter) or from the embedded library (Olive View, Pacoima).
    A test that must not run on a stand-in (the built-in data unreadable) should use
    `real_paper_record`."""
    from pipeline.records import paper_record as resolve

    directory = SHARED_RECORDS if SHARED_RECORDS.is_dir() else None
    cache = {}

    def load(key):
        if key not in cache:
            cache[key] = resolve(key, records_dir=directory)
        return cache[key]

    return load


@pytest.fixture(scope="session")
def real_paper_record(paper_record):
    def load(key):
        record = paper_record(key)
        if record.found_in == "stand-in":
            pytest.skip(f"the real {key} record is not available here")
        return record

    return load


@pytest.fixture(scope="session", params=["numba", "numpy"])
def backend(request) -> str:
    """Each engine test runs on both time loops: the compiled kernel and the NumPy reference.
    Session scope: the kernel compiles (or loads from its cache) once per test session."""
    return request.param



# The longest files first (their wall time in the suite, 3 workers on 2 cores, cold caches, in
# s): pytest-xdist hands whole files to whichever worker is free in collection order
# (--dist loadfile), so the many short files then fill the gaps and no worker is left alone
# with a long file at the end. Files that run commands in subprocesses are ordered like the
# rest: put last, the longest of them (the documentation's examples, the interrupted recipe,
# the dask clusters) ran on one worker while the others had finished.
LONG_FIRST = ("tests/engine/test_plan_references.py",                  # 79
              "tests/test_readme.py",                                  # 77
              "tests/engine/test_torsion.py",                          # 25 (warm: 14)
              "tests/engine/test_plan.py",                             # 68
              "tests/engine/test_stories.py",                          # 65
              "tests/reference/test_opensees_pdelta.py",               # 51
              "tests/reference/test_references.py",                    # 50
              "tests/engine/test_simulate_opensees.py",                # 45
              "tests/studies/test_collapse.py",                        # 44
              "tests/engine/impact/test_contact.py",                   # 39
              "tests/reference/test_opensees_imk.py",                  # 37
              "tests/pipeline/execute/test_executor_interrupt.py",     # 37
              "tests/studies/test_sweeps.py",                          # 36
              "tests/pipeline/test_cluster.py",                        # 34
              "tests/engine/test_isolators.py",                        # 32
              "tests/studies/test_paper_conclusions.py",               # 29
              "tests/pipeline/execute/test_zarr_store.py",             # 24
              "tests/pipeline/assess/test_loss.py",                    # 23
              "tests/engine/loops/test_numba_loop.py",                 # 23
              "tests/pipeline/test_sweep.py",                          # 22
              "tests/engine/test_plan_friction.py",                    # 21
              "tests/studies/common/test_options.py",                  # 20
              "tests/engine/test_building_collapse.py",                # 19
              "tests/studies/test_design.py",                          # 19
              "tests/engine/test_simulate.py",                         # 18
              "tests/engine/test_torsion_references.py",               # 18 (warm: 8)
              "tests/studies/test_torsion.py",                         # 16 (warm: 12)
              "tests/studies/test_suite.py",                           # 15
              "tests/engine/test_impact.py")                           # 14


def pytest_configure(config):
    """Keep the order below: pytest-xdist (3.6 on) would otherwise hand out the files with the
    most tests first, whatever their length (its --no-loadscope-reorder). In the process that
    starts the workers, compile the kernels most tests run once (tests/warm_kernels.py)."""
    if hasattr(config.option, "loadscopereorder"):
        config.option.loadscopereorder = False
    workers = getattr(config.option, "numprocesses", None)
    if workers and not hasattr(config, "workerinput") and not config.option.collectonly:
        from tests.warm_kernels import warm

        warm(Path(str(config.rootpath)))


def pytest_collection_modifyitems(config, items):
    rank = {name: i for i, name in enumerate(LONG_FIRST)}
    root = Path(str(config.rootpath))

    def key(item):
        path = Path(str(item.path)).relative_to(root).as_posix()
        return rank.get(path, len(LONG_FIRST) + 1)

    items.sort(key=key)  # stable: the other files keep their order
