"""What several tests use besides fixtures: paths, archive checks, and how heavy engine tests
and recipes are run. Imported as `from tests.helpers import ...` (fixtures stay in
conftest.py)."""
from pathlib import Path

import numpy as np

PROJECT = Path(__file__).resolve().parents[1]
"""The project's checkout."""
SHARED_RECORDS = PROJECT.parent / "shared" / "records"
"""../shared/records: real AT2 files the project must read in place, never copy."""


NAMED_SCALED_UNITS = {"degree", "yr-1"}
"""Units whose UDUNITS definition is a scaled SI unit by name (degree: pi/180 rad; yr-1: per
year, UDUNITS' year of 365.24 days)."""


def assert_udunits(ds) -> None:
    """Every numeric variable and coordinate of an archive has a `units` string that UDUNITS
    (through cf-units) reads as what it says, or one UDUNITS refuses and long_name repeats;
    text ones have none.

    "Reads as what it says": UDUNITS folds a malformed power into a scale factor ("N m-1.5" is
    1.5 N/m, definition "0.5 kg.s-2"), so a scale in the definition must be written at the
    start of the string itself (as in "9.81 m s-2")."""
    import re

    import cf_units

    for name, var in ds.variables.items():
        units = var.attrs.get("units")
        if var.dtype.kind not in "biufc":  # text: no units (pipeline.archive.variable)
            assert units is None, f"{name}: text with units {units!r}"
            continue
        assert isinstance(units, str) and units, f"{name}: no units"
        try:
            unit = cf_units.Unit(units)
        except ValueError:
            assert units in var.attrs.get("long_name", ""), \
                f"{name}: UDUNITS refuses {units!r} and long_name does not give it"
            continue
        scale = re.match(r"^\s*([-+0-9.eE]+)(?=\s|$)", unit.definition)
        if scale and unit.definition.strip() != "1" and units not in NAMED_SCALED_UNITS:
            assert units.strip().startswith(scale.group(1)), \
                f"{name}: {units!r} reads as {unit.definition!r} in UDUNITS"


NUMPY_SECONDS = 15.0
"""s of a record that the heavy engine tests run on the NumPy loop (~1e4 member-steps/s at
B = 1, 2000x slower than the kernel), and the OpenSees cross-checks on both: the strong
motion, where every peak of the paper's records lies (`strong_part` checks that on the
kernel)."""


def assert_collapse_modes(mode, collapsed) -> None:
    """A study's collapse_mode (a DataArray) labelled as the sweeps label it (int8, units "1",
    the CF flags of engine.results.COLLAPSE_MODES), nonzero exactly where `collapsed` (bool or
    0 / 1, its shape)."""
    from engine.results import COLLAPSE_MODES

    assert mode.dtype == np.int8 and mode.attrs["units"] == "1"
    assert mode.attrs["flag_meanings"] == " ".join(COLLAPSE_MODES)
    assert list(mode.attrs["flag_values"]) == list(range(len(COLLAPSE_MODES)))
    fell = np.asarray(collapsed).astype(bool)
    assert mode.shape == fell.shape
    assert np.all(mode.values[fell] != 0) and np.all(mode.values[~fell] == 0)


def strong_motion(record, backend: str, contact):
    """The record as an engine test should run it on `backend`: whole on the kernel; on the
    NumPy loop its `strong_part`."""
    return record if backend != "numpy" else strong_part(record, contact)


def strong_part(record, contact):
    """The record's first NUMPY_SECONDS, after checking with the kernel that they hold every
    peak of the whole record for `contact` (the impact counts among them)."""
    import engine
    from pipeline.histories import segment

    part = segment(record, NUMPY_SECONDS)
    whole = engine.simulate(record.accel, record.dt, contact, backend="numba")
    cut = engine.simulate(part.accel, part.dt, contact, backend="numba")
    for name, value in whole.peaks().items():
        np.testing.assert_array_equal(getattr(cut, name), value, err_msg=name)
    return part


def recipe_outputs(module, argv: list[str], out: Path) -> Path:
    """Run a recipe's main into `out` (must succeed) and return the folder of its outputs."""
    assert module.main([*argv, "--quiet", "--out", str(out)]) == 0
    # a quick run's outputs go beside a full run's, never over them
    return out / "quick" if "--quick" in argv else out


def run_recipe(module, argv: list[str], out: Path):
    """Run a recipe's main into `out` (must succeed) and return its archive, loaded."""
    import xarray as xr

    with xr.open_dataset(recipe_outputs(module, argv, out) / f"{module.recipe.name}.nc") as ds:
        return ds.load()


PNG_SIGNATURE, PDF_SIGNATURE = b"\x89PNG\r\n\x1a\n", b"%PDF-"


def assert_figure_files(png: Path, pdf: Path) -> None:
    """A recipe's figure written as a PNG and a PDF (what it shows is checked on the Figure
    the recipe's plot(ds) returns: drawn(ax) below)."""
    assert png.read_bytes().startswith(PNG_SIGNATURE), png
    assert pdf.read_bytes().startswith(PDF_SIGNATURE), pdf


def drawn(ax) -> list[tuple[str, np.ndarray, np.ndarray]]:
    """(label, x, y) of every line drawn on a matplotlib Axes, in drawing order (reference
    lines such as axhline included: their x is in axes coordinates)."""
    return [(line.get_label(), np.asarray(line.get_xdata(), float),
             np.asarray(line.get_ydata(), float)) for line in ax.get_lines()]


def variables_page():
    """tools/variables_page.py as a module (tools/ is no package)."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("variables_page",
                                                  PROJECT / "tools" / "variables_page.py")
    page = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(page)
    return page


def assert_on_variables_page(ds, archive: str) -> None:
    """docs/variables.md lists, under `archive` (a study's archive file name), exactly the
    variables of `ds` that the sweep's part of the page does not, each with ds's units
    (tools/variables_page.py; run it with --write --studies when a study's variables change)."""
    page = variables_page()
    text = (PROJECT / "docs" / "variables.md").read_text()
    listed = page.listed_by_archive(text).get(archive)
    fix = "run python tools/variables_page.py --write --studies"
    assert listed is not None, f"docs/variables.md lists no {archive}: {fix}"
    own = {name: units.strip("`") for name, units, _, _ in
           page.own_variables(ds, page.sweep_names(text))}
    assert own == listed, f"{archive}'s variables differ from docs/variables.md's: {fix}"


HANG_SECONDS = 600.0
"""s: how long a test waits for an event (a process started, a part kept, a worker gone)
before it calls the wait hung: a guard against a hang, never a speed check (about a hundred
times those waits on the 2-core development machine, so that a loaded machine does not turn a
test red)."""


def wait_until(ready, what: str, check=None, pause: float = 0.05) -> None:
    """Poll ready() every `pause` s until it is true; check(), when given, runs at each poll
    and asserts what must hold meanwhile (the awaited process still running); pytest.fail
    naming `what` after HANG_SECONDS."""
    import time

    import pytest

    started = time.monotonic()
    while not ready():
        if check is not None:
            check()
        if time.monotonic() - started > HANG_SECONDS:
            pytest.fail(f"{what}: still waiting after {HANG_SECONDS:g} s (hung)")
        time.sleep(pause)
