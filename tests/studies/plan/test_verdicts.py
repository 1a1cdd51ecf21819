"""studies.plan.verdicts: the plan recipe's verdicts counted on a hand-made dataset (1 pair, angles
0/90, fractions 0.7/0.9), and its quantifiers."""

import numpy as np
import pytest
import xarray as xr

from pipeline.assess.outcomes import judged
from studies import plan

CONCLUSIONS = ["4, 5.1", "5.1", "5.1", "5.1", "6", "6"]
VALUES = ("peak_isolator_disp", "peak_floor_accel", "peak_base_accel",
          "peak_interstory_drift", "max_impact_force")
PLANAR, PLAN = 0, 1
NONE, BARE, BUMPERS = 0, 1, 2


def hand_made():
    """Every peak 1 and no impact, except the points set below (angle, fraction indices)."""
    shape = (1, 2, 2, 2, 3)
    data = {name: np.ones(shape) for name in VALUES}
    impacts = np.zeros(shape, dtype=np.int64)
    fit = np.ones(shape[:3], dtype=np.int8)

    def at(model, a, f, barrier, n=0, floor=1.0, base=1.0, drift=1.0, force=0.0):
        impacts[0, a, f, model, barrier] = n
        for name, value in zip(VALUES[1:], (floor, base, drift, force), strict=True):
            data[name][0, a, f, model, barrier] = value

    # planar: both hit, all helped but drift (0.7); only bumpers, amplified (0.9); only
    # bumpers, not amplified (90 degrees, 0.7)
    at(PLANAR, 0, 0, BARE, 3, force=4.0)
    at(PLANAR, 0, 0, BUMPERS, 5, floor=0.8, base=0.5, drift=1.2, force=2.0)
    at(PLANAR, 0, 1, BUMPERS, 2, floor=1.5, drift=1.1, force=1.0)
    at(PLANAR, 1, 0, BUMPERS, 2, floor=0.9, drift=0.9, force=1.0)
    # plan: both hit, nothing helped (0.7); both hit, floor and force helped, drift amplified
    # (0.9); only bumpers, amplified (90 degrees, 0.7)
    at(PLAN, 0, 0, BARE, 3, force=4.0)
    at(PLAN, 0, 0, BUMPERS, 4, floor=1.2, base=1.1, drift=0.9, force=5.0)
    at(PLAN, 0, 1, BARE, 1, force=4.0)
    at(PLAN, 0, 1, BUMPERS, 3, floor=0.7, base=1.05, drift=1.3, force=3.0)
    at(PLAN, 1, 0, BUMPERS, 2, floor=2.0, force=1.0)
    # 90 degrees, 0.9: the bumpers do not fit (not run) while the planar bare wall is hit;
    # it must count nowhere
    fit[0, 1, 1] = 0
    at(PLANAR, 1, 1, BARE, 2, floor=3.0, force=9.0)
    impacts[0, 1, 1, :, BUMPERS] = -1
    for name in VALUES:
        data[name][0, 1, 1, :, BUMPERS] = np.nan
    dims = ("record", "angle", "gap_fraction", "model", "barrier")
    ds = xr.Dataset({name: (dims, values) for name, values in data.items()},
                    coords={"record": ["pair"], "angle": [0.0, 90.0],
                            "gap_fraction": [0.7, 0.9], "model": list(plan.MODELS),
                            "barrier": list(plan.BARRIERS)})
    ds["n_impacts"] = (dims, impacts)
    ds["bumpers_fit"] = (dims[:3], fit)
    ds["angle_gain"] = (("record", "model"), [[1.0, 1.2]])
    return ds


# (planar held, counted), (plan held, counted), the verdict (judged in plan)
EXPECTED = [((0, 0), (1, 1), "agrees"),   # 4, 5.1 at 0.9: planar's only bare hit is unfit
            ((1, 2), (1, 1), "agrees"),   # wide, "may": planar 1/2, plan 1/1
            ((1, 1), (0, 2), "differs"),  # base reduced, "can"
            ((2, 3), (1, 2), "differs"),  # drift amplified, "most": plan's 90 degrees, 0.7
            # (drift 1, a tie) is outside the count, beside it
            ((1, 1), (1, 2), "agrees"),   # force reduced, "may"
            ((1, 1), (0, 1), "differs")]  # narrower more effective, per (pair, angle)


def test_verdict_counting():
    found = [v.as_dict() for v in plan.check(hand_made())]
    assert [v["conclusion"] for v in found] == CONCLUSIONS
    for v, (planar, inplan, word) in zip(found, EXPECTED, strict=True):
        got = [(v["numbers"][m]["held"], v["numbers"][m]["counted"]) for m in plan.MODELS]
        assert got == [planar, inplan], v["claim"]
        assert v["verdict"] == word, v["claim"]
    assert found[0]["numbers"]["planar"]["verdict"] == "not tested"
    assert found[1]["numbers"]["planar"]["verdict"] == "agrees"  # "may": one case is enough
    assert found[3]["numbers"]["plan"]["tie_cases"] == 1
    assert "1 ties within 2% not counted" in found[3]["finding"]
    assert "planar: 1/2 (50%, median x1.20)" in found[1]["finding"]
    assert "in plan: 1/1 (100%, median x2.00)" in found[1]["finding"]
    assert found[1]["numbers"]["planar"]["amplification"] == {"median": 1.2, "min": 0.9,
                                                              "max": 1.5}
    assert found[1]["numbers"]["by_gap_fraction"]["plan"] == {"0.7": [1, 1], "0.9": [0, 0]}
    assert found[3]["numbers"]["by_gap_fraction"]["planar"] == {"0.7": [1, 2], "0.9": [1, 1]}
    gain = found[0]["numbers"]["plan_vs_planar"][plan.GAIN_KEYS["plan"]]
    assert gain["median"] == pytest.approx(1.2) and gain["points"] == 1


def test_quantifiers():
    assert judged("every", 3, 3) and not judged("every", 2, 3)
    assert judged("some", 1, 9) and not judged("some", 0, 9)
    assert judged("most", 2, 3) and not judged("most", 1, 2)
    assert judged("most", 0, 0) is None
