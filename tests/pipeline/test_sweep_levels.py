"""Intensity as an excitation dimension: a sweep's `level`, swept like the angle, times each
record's `factors` (a code suite's MCE_R factors), run by the one executor.

The engine's `scale` is the independent reference: a member at level l of a record with
factor f must give, bit for bit, the engine run of that record scaled by f * l.
"""
import numpy as np
import pytest

import engine
import pipeline
from pipeline.errors import SweepError
from tests.pipeline.small_sweep import DT, RECORDS

LEVELS = [0.5, 1.0, 1.5]
GAPS = [0.06, 0.10]
FACTORS = [1.7, 0.6]


@pytest.fixture(scope="module")
def leveled():
    return pipeline.sweep(RECORDS, gap=GAPS, thickness=0.03, dt=DT, level=LEVELS,
                          factors=FACTORS, baseline=True, unconstrained=True, quiet=True)


def test_each_member_is_the_engine_run_at_factor_times_level(leveled):
    for r, rec in enumerate(RECORDS):
        scale = FACTORS[r] * np.repeat(LEVELS, len(GAPS))
        gaps = np.tile(GAPS, len(LEVELS))
        direct = engine.simulate(rec.accel, rec.dt, engine.Contact.bumper(gaps, thickness=0.03),
                                 dt=DT, scale=scale)
        swept = leveled.peak_isolator_disp.isel(record=r).values.ravel()
        assert swept.tobytes() == direct.peak_isolator_disp.tobytes()
        free = engine.simulate(rec.accel, rec.dt, engine.Contact.none(len(LEVELS)), dt=DT,
                               scale=FACTORS[r] * np.array(LEVELS))
        assert leveled.unconstrained_peak_total_accel.isel(record=r).values.tobytes() \
            == free.peak_total_accel.tobytes()


def test_blocks_repeat_per_level_and_the_archive_says_how(leveled):
    assert leveled.peak_isolator_disp.dims == ("record", "level", "gap")
    assert leveled.baseline_peak_isolator_disp.dims == ("record", "level", "gap")
    assert leveled.unconstrained_peak_isolator_disp.dims == ("record", "level")
    assert leveled.record_factor.values.tolist() == FACTORS
    assert leveled.level.attrs["units"] == "1"
    # a stronger shaking moves the building farther where there is no wall
    free = leveled.unconstrained_peak_isolator_disp.values
    assert np.all(np.diff(free, axis=1) > 0)


def test_no_level_leaves_the_records_as_they_are():
    plain = pipeline.sweep(RECORDS[:1], gap=GAPS, dt=DT, quiet=True)
    one = pipeline.sweep(RECORDS[:1], gap=GAPS, dt=DT, level=1.0, quiet=True)
    assert "level" not in plain.coords and float(one.level) == 1.0
    assert plain.peak_total_accel.values.tobytes() == one.peak_total_accel.values.tobytes()


def test_the_factor_is_part_of_what_a_work_folder_resumes(tmp_path):
    work = tmp_path / "work"
    a = pipeline.sweep(RECORDS[:1], gap=GAPS, dt=DT, factors=[1.0], work_dir=work, quiet=True)
    b = pipeline.sweep(RECORDS[:1], gap=GAPS, dt=DT, factors=[2.0], work_dir=work, quiet=True)
    assert not np.array_equal(a.peak_isolator_disp.values, b.peak_isolator_disp.values)
    assert len(list(work.glob("*.npz"))) == 2  # none reused across factors


@pytest.mark.parametrize("factors, words", [([1.0], "2 numbers"), ([1.0, -2.0], "positive"),
                                            ([1.0, np.nan], "positive"), ("x", "2 numbers")])
def test_bad_factors_are_refused_in_one_line(factors, words):
    with pytest.raises(SweepError, match=words):
        pipeline.sweep(RECORDS, gap=GAPS, dt=DT, factors=factors, quiet=True)


def test_bad_levels_are_refused():
    with pytest.raises(SweepError, match="level"):
        pipeline.sweep(RECORDS, gap=GAPS, dt=DT, level=[0.0, 1.0], quiet=True)


def test_a_finished_sweep_forgets_its_work_folder(tmp_path):
    from pipeline.execute.netcdf_store import WorkFolder

    out = tmp_path / "a.nc"
    pipeline.sweep(RECORDS[:1], gap=GAPS, dt=DT, out=out, quiet=True)
    work = out.with_name("a.nc.work")
    assert not work.exists()
    assert not [f for f in WorkFolder.READ if f.parent == work]  # nothing kept in memory
