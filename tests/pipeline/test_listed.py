"""Members listed one by one (pipeline.listed): a table shared by every record, or one per
record, run by the one executor; each member must be the engine's run of that wall alone."""
import numpy as np
import pytest

import engine
import pipeline
from pipeline.errors import SweepError
from tests.pipeline.small_sweep import DT, RECORDS

NAN = np.nan
SHARED = {"law": ["none", "linear", "bumper"], "gap": [NAN, 0.10, 0.10],
          "thickness": [NAN, NAN, 0.03]}


def test_a_shared_table_is_the_grid_it_lists():
    listed = pipeline.sweep(RECORDS, members=SHARED, dt=DT, quiet=True)
    grid = pipeline.sweep(RECORDS, gap=0.10, thickness=0.03, dt=DT, baseline=True,
                          unconstrained=True, quiet=True)
    for name in ("peak_total_accel", "peak_isolator_disp", "max_impact_force", "n_impacts"):
        got = listed[name].transpose("member", ...).values
        for k, prefix in enumerate(("unconstrained_", "baseline_", "")):
            assert got[k].tobytes() == grid[prefix + name].values.tobytes(), (name, prefix)
    assert listed.law.values.tolist() == SHARED["law"]
    assert listed.gap.attrs["units"] == "m"


def test_each_record_runs_its_own_members(tmp_path):
    gaps = np.array([[0.06, 0.12], [0.08, 0.14]])
    table = {"law": ["linear", "bumper"], "gap": gaps, "thickness": [NAN, 0.03]}
    ds = pipeline.sweep(RECORDS, members=table, dt=DT, quiet=True)
    assert ds.gap.dims == ("record", "member")
    for r, rec in enumerate(RECORDS):
        walls = engine.Contact.concat([engine.Contact.linear([gaps[r, 0]]),
                                       engine.Contact.bumper([gaps[r, 1]], thickness=0.03)])
        alone = engine.simulate(rec.accel, rec.dt, walls, dt=DT)
        assert ds.max_impact_force.isel(record=r).values.tobytes() \
            == alone.max_impact_force.tobytes()
    stored = pipeline.sweep(RECORDS, members=table, dt=DT, quiet=True,
                            out=tmp_path / "listed.zarr")
    assert stored.peak_isolator_disp.values.tobytes() == ds.peak_isolator_disp.values.tobytes()


@pytest.mark.parametrize("table, words", [
    ({"gap": [0.1]}, "'law'"),
    ({"law": ["linear"], "gap": [0.1], "colour": [1.0]}, "no member column"),
    ({"law": ["steel"], "gap": [0.1]}, "unknown law"),
    ({"law": ["none"], "gap": [0.1]}, "does not apply"),
    ({"law": ["linear"]}, "gap is required"),
    ({"law": ["linear"], "gap": [[0.1], [0.2], [0.3]]}, "one row per record"),
    ({"law": ["linear"], "gap": [-0.1]}, "gap"),
    # as a grid's: more bumpers than a moat wall holds (issue 40)
    ({"law": ["bumper", "bumper"], "gap": [0.1, 0.1], "n_bumpers": [4, 1000]},
     "n_bumpers 1000: 1000 pads of 150 mm a side"),
])
def test_bad_tables_are_refused_in_one_line(table, words):
    with pytest.raises(SweepError, match=words):
        pipeline.sweep(RECORDS, members=table, dt=DT, quiet=True)


def test_a_table_excludes_grid_parameters():
    with pytest.raises(SweepError, match="members lists every member"):
        pipeline.sweep(RECORDS, members=SHARED, gap=0.1, dt=DT, quiet=True)


def test_a_member_listed_twice_runs_once(count_simulated):
    table = {"law": ["linear", "none", "linear", "none"], "gap": [0.10, NAN, 0.10, NAN]}
    ds = pipeline.sweep(RECORDS[:1], members=table, dt=DT, quiet=True)
    assert sum(count_simulated) == 2
    values = ds.peak_total_accel.isel(record=0).values
    assert values[0].tobytes() == values[2].tobytes() and values[1].tobytes() == values[3].tobytes()
    assert not np.array_equal(values[0], values[1])
