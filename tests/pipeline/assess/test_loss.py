"""pipeline.assess.loss: pelicun's FEMA P-58 repair cost of one component against a hand
calculation from that component's fragility and consequence data. (The hazard's time-based
integration: test_hazard.py.)"""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.stats import norm

from engine.units import G


def test_pelicuns_repair_cost_is_the_hand_calculation(tmp_path):
    """Four pendant lights (FEMA P-58 C.30.34.001, one damage state, Peak Floor Acceleration
    median 0.6 g, beta 0.4, non-directional, read at the floor above) on a one-story building
    whose floor above peaks at 0.5 g both ways in every run: pelicun's non-directional demand
    is 1.2 x 0.5 g = 0.6 g (FEMA P-58-1 section 5.2.5's factor), so P(DS1) = 1/2; the repair
    costs 2.3 USD_2011 a light (the database's median for up to five, lognormal, dispersion
    0.636941), so the mean cost is 1/2 x 4 x 2.3 x exp(0.636941^2 / 2). Collapse and
    irreparable drift out of reach."""
    loss = pytest.importorskip("pipeline.assess.loss")
    pytest.importorskip("pelicun")
    table = tmp_path / "one.csv"
    table.write_text("component,quantity,per,unit,location,direction,description\n"
                     "C.30.34.001,4,story,ea,stories,0,pendant lights\n")
    rows = loss.read_inventory(table)
    runs = 8
    pfa = np.full((runs, 2, 2), 0.5 * G)
    pid = np.full((runs, 1, 2), 1e-4)  # far below yield: no residual drift
    samples = 5000
    out = loss.losses([loss.Group(pfa, pid, -20.0)], rows, stories=1, floor_area=100.0,
                      yield_drift=0.01, samples=samples, seed=3)
    cost = out["repair_cost"][0]
    assert out["collapse_probability"][0] < 1e-80 and not out["irreparable"].any()
    expected = 0.5 * 4 * 2.3 * math.exp(0.636941 ** 2 / 2)
    # the share damaged is a binomial of p = 1/2 over the samples: within 4 standard errors
    damaged = np.mean(cost > 0)
    assert abs(damaged - 0.5) < 4 * math.sqrt(0.25 / samples)
    assert cost.mean() == pytest.approx(expected, rel=0.05)
    # the median unit cost of the damaged lights is the database's 2.3
    assert np.median(cost[cost > 0]) / 4 == pytest.approx(2.3, rel=0.05)


def test_collapse_enters_by_its_probability():
    loss = pytest.importorskip("pipeline.assess.loss")
    pytest.importorskip("pelicun")
    rows = loss.read_inventory()
    rng = np.random.default_rng(0)
    pfa = rng.lognormal(math.log(0.3 * G), 0.2, (10, 3, 2))
    pid = rng.lognormal(math.log(0.003), 0.2, (10, 2, 2))
    done = []
    out = loss.losses([loss.Group(pfa, pid, 0.5), None, loss.Group(pfa, pid, -1.0)], rows,
                      stories=2, floor_area=500.0, yield_drift=0.01, samples=300, seed=5,
                      progress=lambda: done.append(1))
    assert len(done) == 2  # progress once per group assessed (the loss study's progress line)
    assert out["collapse_probability"][[0, 2]] == pytest.approx(norm.cdf([0.5, -1.0]))
    assert out["replacement_cost"] == loss.COST_PER_M2 * 500.0 * 2
    # common random numbers: the same demands give the same realizations whatever the
    # collapse probability
    np.testing.assert_array_equal(out["repair_cost"][0], out["repair_cost"][2])
    assert np.all(out["repair_cost"][0] < out["replacement_cost"])
    assert np.isnan(out["repair_cost"][1]).all() and np.isnan(out["collapse_probability"][1])


def test_a_group_assessed_among_others_is_the_group_assessed_alone(monkeypatch):
    """The groups share pelicun's assessments (BATCH at a time, here 2 so that the three
    groups span two batches, the second in a helper process on two cores), each drawing what
    it would draw alone: the second group's
    irreparable realizations (its demands' residual drift against the capacities) are the
    same realizations, and its mean repair cost agrees within the consequences' sampling
    error (pelicun draws those for the components and damage states the batch reaches)."""
    loss = pytest.importorskip("pipeline.assess.loss")
    pytest.importorskip("pelicun")
    monkeypatch.setattr(loss, "BATCH", 2)
    rows = loss.read_inventory()
    rng = np.random.default_rng(1)
    groups = [loss.Group(rng.lognormal(math.log(a * G), 0.3, (12, 3, 2)),
                         rng.lognormal(math.log(d), 0.4, (12, 2, 2)), -2.0)
              for a, d in ((0.2, 0.002), (0.5, 0.012), (0.9, 0.02))]
    kw = {"stories": 2, "floor_area": 500.0, "yield_drift": 0.005, "samples": 400, "seed": 2}
    together = loss.losses(groups, rows, **kw)
    alone = loss.losses(groups[1:2], rows, **kw)
    np.testing.assert_array_equal(together["irreparable"][1], alone["irreparable"][0])
    cost, ref = together["repair_cost"][1], alone["repair_cost"][0]
    error = math.hypot(cost.std(), ref.std()) / math.sqrt(cost.size)
    assert abs(cost.mean() - ref.mean()) < 4 * error
    # the demands differ enough to reach the irreparable drift in some groups only
    assert not together["irreparable"][0].any() and 0 < together["irreparable"][1].mean() < 1
    # each run's own demands too: its mean cost over its realizations (100 of 400, 8 or 9 a
    # run), within the consequences' sampling error of the group assessed alone
    runs, ref_runs = together["run_repair_cost"][1], alone["run_repair_cost"][0]
    assert runs.shape == (12,) and (runs > 0).all()
    np.testing.assert_allclose(runs, ref_runs, rtol=0.1)
    # the runs' mean and the fitted model's agree within the model's extrapolation
    assert runs.mean() == pytest.approx(cost.mean(), rel=0.2)
    # the second batch (the third group) went to the helper process where there are two
    # cores: its numbers are those of the group assessed alone here, bit for bit
    third = loss.losses(groups[2:], rows, **kw)
    for name in ("repair_cost", "repair_time", "run_repair_cost"):
        np.testing.assert_array_equal(together[name][2], third[name][0])


def test_a_bad_inventory_is_refused_in_one_line(tmp_path):
    loss = pytest.importorskip("pipeline.assess.loss")
    bad = tmp_path / "bad.csv"
    bad.write_text("component,quantity,per,unit,location,direction,description\n"
                   "C.30.34.001,4,floor,ea,stories,0,lights\n")
    with pytest.raises(ValueError, match="'per' is m2, story or building_m2"):
        loss.read_inventory(bad)


def test_losses_do_not_depend_on_pythons_hash_seed():
    """The same inputs give the same realizations in any process (pelicun built its default
    loss map from a set: the order of its draws followed the hash seed)."""
    import contextlib
    import io
    import os
    import subprocess
    import sys

    pytest.importorskip("pelicun")
    code = (
        "import numpy as np\n"
        "from pipeline.assess import loss\n"
        "pfa = np.full((6, 3, 2), 6.0) * np.linspace(0.8, 1.2, 6)[:, None, None]\n"
        "pid = np.full((6, 2, 2), 0.004) * np.linspace(0.8, 1.2, 6)[:, None, None]\n"
        "out = loss.losses([loss.Group(pfa, pid, -1.0)], loss.read_inventory(), stories=2,\n"
        "                  floor_area=300.0, yield_drift=0.005, samples=60, seed=4)\n"
        "print(out['repair_cost'].tobytes().hex())\n")
    there = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                           check=True, env={**os.environ, "PYTHONHASHSEED": "1"}).stdout
    here = io.StringIO()
    with contextlib.redirect_stdout(here):
        exec(code, {})
    # this process's hash seed is random (pytest's, or a fixed one other than 1)
    assert sys.flags.hash_randomization or os.environ.get("PYTHONHASHSEED") != "1"
    assert here.getvalue() == there


def test_the_repair_cost_by_component_group_sums_it():
    """Issue 38: the repair cost split by component group (COMPONENT_GROUPS: acceleration-
    sensitive components, drift-sensitive ones, the replacement of an irreparable building)
    sums, realization by realization, to pelicun's repair cost given no collapse; light
    shaking with small drifts damages the acceleration-sensitive components and no more; a
    component is grouped by its FEMA P-58 fragility's demand."""
    loss = pytest.importorskip("pipeline.assess.loss")
    pytest.importorskip("pelicun")
    assert loss.component_group("C.30.34.001") == 0    # pendant lights: floor acceleration
    assert loss.component_group("B.10.35.021") == 1    # a moment connection: story drift
    assert loss.component_group("replacement") == 2
    rng = np.random.default_rng(0)
    strong = loss.Group(rng.lognormal(math.log(0.8 * G), 0.3, (10, 3, 2)),
                        rng.lognormal(math.log(0.012), 0.4, (10, 2, 2)), -3.0)
    light = loss.Group(rng.lognormal(math.log(0.5 * G), 0.1, (10, 3, 2)),
                       np.full((10, 2, 2), 1e-4) * rng.lognormal(0.0, 0.1, (10, 1, 1)), -3.0)
    out = loss.losses([strong, light], loss.read_inventory(), stories=2, floor_area=500.0,
                      yield_drift=0.01, samples=300, seed=1)
    parts = out["repair_cost_by_group"]
    np.testing.assert_allclose(parts.sum(axis=-1), out["repair_cost"], rtol=1e-12)
    assert (parts[0] > 0).any(axis=0).all()  # strong shaking: every group somewhere
    assert parts[1, :, 0].mean() > 0 and np.all(parts[1, :, 1:] == 0)


def test_each_runs_mean_is_over_the_realizations_that_took_its_demands():
    from pipeline.assess import loss as p58

    # realization k takes run k mod R: 7 realizations on 3 runs -> runs 0, 1, 2, 0, 1, 2, 0
    x = np.array([[1.0, 2.0, 3.0, 5.0, 4.0, 3.0, 9.0], [0.0] * 7])
    got = p58.run_means(x, [3, 2])
    assert got[0].tolist() == pytest.approx([5.0, 3.0, 3.0])
    assert got[1, :2].tolist() == [0.0, 0.0] and np.isnan(got[1, 2])
