"""Shared fixtures: the paper's records as the record layer resolves them, and the backend
every engine test runs on. Helpers that are not fixtures are in tests/helpers.py."""
from pathlib import Path

import pytest

from tests.helpers import SHARED_RECORDS


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



# The longest files first (their measured share of the suite, warm, in s): pytest-xdist hands
# whole files to whichever worker is free in collection order (--dist loadfile), so the many
# short files then fill the gaps. The files that run commands in subprocesses go last: by then
# the compiled kernels are in the disk cache, and a subprocess loads instead of compiling.
LONG_FIRST = ("tests/reference/test_references.py",        # 35
              "tests/engine/test_opensees.py",             # 34
              "tests/engine/test_plan_references.py",      # 34
              "tests/reference/test_opensees_pdelta.py",   # 21
              "tests/reference/test_opensees_imk.py",      # 18
              "tests/engine/test_stories.py",              # 23
              "tests/engine/test_plan.py",                 # 21
              "tests/studies/test_sweeps.py",              # 20
              "tests/studies/test_paper_conclusions.py",   # 19
              "tests/engine/test_model_edges.py")          # 18
SUBPROCESSES_LAST = ("tests/pipeline/test_cluster.py", "tests/pipeline/test_tls.py",
                     "tests/pipeline/test_interrupt.py", "tests/studies/test_cli.py",
                     "tests/studies/test_bumpers_command.py", "tests/test_readme.py")


def pytest_collection_modifyitems(config, items):
    rank = {name: i for i, name in enumerate(LONG_FIRST)}
    rank.update({name: len(LONG_FIRST) + 2 + i for i, name in enumerate(SUBPROCESSES_LAST)})
    root = Path(str(config.rootpath))

    def key(item):
        path = Path(str(item.path)).relative_to(root).as_posix()
        return rank.get(path, len(LONG_FIRST) + 1)

    items.sort(key=key)  # stable: the other files keep their order
