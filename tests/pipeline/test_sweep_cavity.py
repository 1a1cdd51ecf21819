"""The wall cavity (paper 5.3) as a sweep parameter of the bumper law."""
from __future__ import annotations

import numpy as np
import pytest

import engine
import pipeline
from pipeline.errors import SweepError
from pipeline.records import load_record
from studies import sweep as sweep_cli


def test_cavity_member_equals_the_engine(tmp_path):
    """A swept cavity is a dimension with its declared unit, and each member is exactly the
    engine's bumper with that cavity; a deeper cavity leaves more clear gap, so fewer or
    later impacts and less indentation."""
    cavities = [0.0, 0.01, 0.02]
    ds = pipeline.sweep(["pacoima"], gap=0.20, thickness=0.05, cavity=cavities, quiet=True)
    assert ds.cavity.dims == ("cavity",) and ds.cavity.attrs["units"] == "m"
    assert "cavity" in ds.cavity.attrs["long_name"]
    rec = load_record("pacoima")
    res = engine.simulate(rec.accel, rec.dt,
                          engine.Contact.bumper(0.20, thickness=0.05, cavity=cavities))
    np.testing.assert_array_equal(ds.peak_total_accel.sel(record="pacoima").values,
                                  res.peak_total_accel)
    np.testing.assert_array_equal(ds.max_indentation.sel(record="pacoima").values,
                                  res.max_indentation)
    assert res.max_indentation[0] > res.max_indentation[2]


def test_cavity_fixed_is_a_scalar_coordinate_of_bumper_archives_only():
    ds = pipeline.sweep(["pacoima"], gap=[0.2, 0.3], quiet=True, batch_size=4)
    assert ds.cavity.ndim == 0 and float(ds.cavity) == 0.0
    bare = pipeline.sweep(["pacoima"], gap=[0.2, 0.3], impact="linear", quiet=True)
    assert "cavity" not in bare.coords


@pytest.mark.parametrize("kwargs, match", [
    ({"cavity": -0.01, "thickness": 0.05}, "cavity"),
    ({"cavity": 0.05, "thickness": 0.05}, "cavity must be smaller than thickness"),
    ({"cavity": 0.01, "impact": "linear"}, "cavity applies to impact='bumper' only"),
])
def test_bad_cavities_are_refused_before_compute(kwargs, match):
    with pytest.raises(SweepError, match=match):
        pipeline.sweep(["pacoima"], gap=0.2, quiet=True, **kwargs)


def test_command_line_cavity_cm(tmp_path):
    out = tmp_path / "cav.nc"
    assert sweep_cli.main(["--records", "pacoima", "--gap-cm", "20", "--cavity-cm", "0", "1",
                           "--out", str(out), "--quiet"]) == 0
    import xarray as xr

    with xr.open_dataset(out) as ds:
        np.testing.assert_allclose(ds.cavity.values, [0.0, 0.01])
