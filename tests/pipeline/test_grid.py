"""The sweep's grid (pipeline/grid.py) refuses bad input before any compute, in one error
naming the parameter: gaps, bumper sizes, material values, dt, laws and their parameters,
records, workers and batches."""

import pytest

import pipeline
from pipeline.errors import SweepError
from tests.pipeline.small_sweep import RECORDS, SMALL, no_compute


@pytest.mark.parametrize("change, match", [
    ({"gap": [0.1, -0.05]}, "gap"),
    ({"gap": 0.0}, "gap"),
    ({"thickness": 0.06}, "thickness"),
    ({"thickness": [0.03, 0.2]}, "thickness"),
    ({"strain": 0.0}, "strain"),
    ({"strain": [0.5, 1.2]}, "strain"),
    ({"cor": 0.0}, "cor"),
    ({"cor": 1.5}, "cor"),
    ({"wall_k": 0.0}, "wall_k"),
    ({"wall_k": -1e9}, "wall_k"),
    ({"n_bumpers": 0}, "n_bumpers"),
    ({"n_bumpers": [4, 2.5]}, "n_bumpers"),
    ({"dt": 0.05}, "dt"),
    ({"dt": -0.001}, "dt"),
    ({"dt": 1e-9}, r"dt = 1e-09 s is implausible \(a 40 s record would take 4e\+10 steps\): "
                   r"give a step of at least 1e-06 s"),  # a run of days (issue 40)
    ({"n_bumpers": [4, 1000]}, "n_bumpers 1000: 1000 pads of 150 mm"),  # an 18 m wall
    ({"impact": "elastic"}, "impact"),
    ({"impact": "linear"}, "thickness"),  # bumper-only parameter given to another law
    ({"impact": "jankowski", "thickness": None, "n_bumpers": None}, "wall_k"),  # required
    ({"impact": "linear", "thickness": None, "n_bumpers": None, "baseline": True}, "baseline"),
    ({"gap": [0.1, 0.1]}, "gap"),
    ({"records": ["no-such-record-anywhere"]}, "records"),
    ({"records": [RECORDS[0], RECORDS[0]]}, "records"),
    ({"workers": -1}, "workers"),
    ({"batch_size": 0}, "batch_size"),
])
def test_bad_input_fails_fast_naming_the_parameter(change, match, monkeypatch):
    no_compute(monkeypatch)
    kwargs = {"records": RECORDS, **SMALL, "workers": 1, "quiet": True, **change}
    with pytest.raises(SweepError, match=match):
        pipeline.sweep(**kwargs)


def test_a_one_law_batch_gets_the_contact_it_gets_among_other_laws():
    """contact_for's shortcut for members of one law (no regrouping) gives every array of the
    Contact those members get when mixed with another law's, bit for bit, in member order."""
    from dataclasses import fields

    import numpy as np

    from pipeline.grid import contact_for, make_grid

    grid = make_grid([0.15, 0.2], n_bumpers=[4, 8], thickness=0.05, baseline=True,
                     unconstrained=True)
    members = grid.members
    bumpers = np.flatnonzero(members["law"] == "bumper")
    assert 0 < bumpers.size < members.size  # the grid mixes laws
    mixed, alone = contact_for(members), contact_for(members[bumpers])
    for field in fields(alone):
        np.testing.assert_array_equal(getattr(alone, field.name),
                                      getattr(mixed, field.name)[bumpers], err_msg=field.name)
