"""pipeline.histories with real numbers: a history's maxima are the engine's peaks, every k-th
step kept, records of different lengths on one time axis, bad configurations refused."""
import numpy as np
import pytest

from pipeline.errors import SweepError
from pipeline.histories import concat_records, histories

PEAKS = ("peak_total_accel", "peak_interstory_drift", "peak_isolator_disp", "max_indentation",
         "max_impact_force", "n_impacts")
CONFIGS = ["no_pounding", "no_bumpers", "bumpers", "no_bumpers_at_paper_gap",
           "bumpers_at_paper_gap"]


def configurations(gap):
    return {"no_pounding": {"impact": "none"},
            "no_bumpers": {"impact": "linear", "gap": gap},
            "bumpers": {"impact": "bumper", "gap": gap, "thickness": 0.05, "n_bumpers": 4}}


@pytest.fixture(scope="module")
def segment_run(paper_record):
    """The first 6 s of Pacoima Dam (its pulse) at a 12 cm gap, every step kept."""
    return histories(paper_record("pacoima"), configurations(0.12), every=1, duration=6.0)


def test_history_maxima_are_the_peaks(segment_run):
    ds = segment_run
    assert list(ds.configuration.values) == CONFIGS[:3]
    np.testing.assert_allclose(ds.time[1] - ds.time[0], 5e-4)
    assert float(ds.time[-1]) == pytest.approx(6.0)
    assert (ds.n_impacts.sel(configuration=["no_bumpers", "bumpers"]) > 0).all()
    np.testing.assert_array_equal(abs(ds.total_accel).max("time"), ds.peak_total_accel)
    np.testing.assert_array_equal(abs(ds.isolator_disp).max("time"), ds.peak_isolator_disp)
    np.testing.assert_array_equal(ds.impact_force.max("time"), ds.max_impact_force)
    np.testing.assert_array_equal(ds.indentation.max("time"), ds.max_indentation)
    assert (ds.impact_force.sel(configuration="no_pounding") == 0).all()
    # Past the crush limit the bumpers bear on the wall; below it the force is k_imp d^2.65.
    bump = ds.sel(configuration="bumpers")
    assert float(bump.clear_gap) == pytest.approx(0.07)
    assert float(bump.crush_indentation) == pytest.approx(0.04)
    for name in (*ds.data_vars, *ds.coords):  # numbers carry units, text none (CF)
        assert ("units" in ds[name].attrs) == (ds[name].dtype.kind in "biufc"), name
        assert "long_name" in ds[name].attrs, name
    assert "first 6 s" in ds.attrs["record_segment"]
    assert "linear(gap=0.12" in ds.attrs["configurations"]


def test_every_keeps_every_kth_step(segment_run, paper_record):
    coarse = histories(paper_record("pacoima"), configurations(0.12), every=4, duration=6.0)
    for name in ("total_accel", "impact_force", "indentation", "isolator_disp"):
        every_4th = segment_run[name].isel(time=slice(None, None, 4))
        np.testing.assert_array_equal(coarse[name], every_4th)
    for name in PEAKS:  # the peaks do not depend on the output interval
        np.testing.assert_array_equal(coarse[name], segment_run[name])

    # Records of different lengths share one time axis, NaN after the shorter one's end.
    short = histories(paper_record("kobe"), configurations(0.12), every=4, duration=3.0)
    both = concat_records([coarse, short])
    assert list(both.record.values) == ["pacoima", "kobe"]
    np.testing.assert_allclose(both.history_end, [6.0, 3.0])
    assert both.impact_force.sel(record="kobe", time=slice(3.01, None)).isnull().all()
    assert not both.impact_force.sel(record="pacoima").isnull().any()
    assert "NaN after the end" in both.impact_force.attrs["fill"]
    for name in PEAKS:
        assert not both[name].isnull().any(), name
    cut = concat_records([coarse, short], t_end=2.0)
    assert float(cut.time[-1]) == pytest.approx(2.0)


@pytest.mark.parametrize("configs, message", [
    ({"a": {"impact": "bumper", "gap": 0.2, "colour": 1}}, "colour"),
    ({"a": {"impact": "none", "gap": 0.2}}, "gap"),
    ({"a": {"impact": "bumper", "gap": [0.2, 0.3]}}, "one value"),
    ({"a": {"impact": "linear", "gap": 0.2, "thickness": 0.05}}, "thickness"),
    ({"a": {"impact": "rubber", "gap": 0.2}}, "impact"),
    ({"a": {"impact": "bumper", "gap": 0.04}}, "thickness"),
    ({}, "configurations"),
])
def test_bad_configurations_fail_before_compute(configs, message):
    with pytest.raises(SweepError, match=message):
        histories("pacoima", configs)


def test_one_record_at_a_time():
    with pytest.raises(SweepError, match="one record"):
        histories(["pacoima", "olive_view"], configurations(0.2))
