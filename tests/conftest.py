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


# Test files that compile the same rarely used kernels (numba, cached on disk once compiled)
# run in one process of the parallel suite (pytest-xdist, --dist loadgroup), so that the
# kernels compile once rather than once per process: the plan kernel, and the kernels of
# buildings other than the paper's (1, 8 and 20 stories). Every other file is a group of its
# own, as --dist loadfile would make it (its module fixtures run once).
KERNEL_GROUPS = {
    "plan": ("tests/engine/test_plan.py", "tests/engine/test_plan_references.py",
             "tests/pipeline/test_plan_sweep.py", "tests/studies/test_plan_recipe.py"),
    "heights": ("tests/engine/test_stories.py", "tests/engine/test_isolators.py",
                "tests/reference/test_references.py"),
}
_GROUP_OF = {path: group for group, paths in KERNEL_GROUPS.items() for path in paths}


@pytest.hookimpl(tryfirst=True)  # before pytest-xdist reads the groups off the items
def pytest_collection_modifyitems(config, items):
    root = Path(__file__).resolve().parents[1]
    for item in items:
        path = Path(str(item.fspath)).resolve().relative_to(root).as_posix()
        item.add_marker(pytest.mark.xdist_group(_GROUP_OF.get(path, path)))
