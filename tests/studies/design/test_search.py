"""studies.design.search: the constraints on known numbers, ties to fewer bumpers then the stiffer
wall, the weighted statistics, the collapses counted by mode."""
from __future__ import annotations

import numpy as np
import pytest

from pipeline.assess.outcomes import weighted_quantiles
from pipeline.assess.validity import FLAGS
from studies.design import search, space

# ---------------------------------------------------------------- constraints, ranking


def stats_of(**columns) -> dict:
    """Statistics (L = 3 levels, K candidates) from (K,) columns per level name."""
    k = len(next(iter(columns.values()))[0])
    out = {name: np.zeros((3, k)) for name in search.STAT_TEXT}
    for name, rows in columns.items():
        out[name] = np.asarray(rows, float)
    return out


def test_constraints_filter_known_numbers():
    zero = [0.0] * 4
    stats = stats_of(
        median_peak_floor_accel=[zero, zero, [5.0, 4.0, 3.0, 2.0]],
        p84_peak_floor_accel=[zero, zero, [6.0, 5.0, 4.0, 3.0]],
        fraction_within_limits=[zero, zero, [0.9, 0.9, 0.8, 0.5]],
        fraction_uncrushed=[zero, zero, [1.0, 1.0, 0.9, 0.6]],
        fraction_contact=[[0.0, 0.1, 0.0, 0.0], zero, zero],
        fraction_hurt=[zero, [0.0, 0.0, 0.3, 0.0], zero],
        fraction_valid=[zero, zero, [1.0] * 4])
    new = search.judge(stats, space.Criteria(), [4] * 4, [1.5e9] * 4)
    # 1: contact at the service level; 2 and 3: within limits under < 84%
    assert new["feasible"].tolist() == [True, False, False, False]
    assert new["rank"].tolist() == [1, 0, 0, 0]
    assert new["margins"]["within_limits"] == pytest.approx([0.06, 0.06, -0.04, -0.34])
    # the old criteria (uncrushed only, the service level free) admit 2 as well: it wins
    old = search.judge(stats, space.Criteria("median", stress_limit=False, service_contact=1.0),
                       [4] * 4, [1.5e9] * 4)
    assert old["rank"].tolist() == [3, 2, 1, 0]
    # hurt at the design level under at most 20%: 2 is out again; p84 as the objective
    capped = search.judge(stats, space.Criteria(stress_limit=False, service_contact=1.0,
                                                 hurt_design=0.2, objective="p84"),
                          [4] * 4, [1.5e9] * 4)
    assert capped["rank"].tolist() == [2, 1, 0, 0]
    assert capped["objective"].tolist() == [6.0, 5.0, 4.0, 3.0]


def test_ties_go_to_fewer_bumpers_then_the_stiffer_wall():
    rank = search.ranking([1.0, 1.0, 1.0, 0.5], [2.0] * 4, [8, 4, 4, 4],
                          [2.5e9, 5e8, 2.5e9, 1e9], [True, True, True, False])
    assert rank.tolist() == [3, 2, 1, 0]


def test_collapses_counted_by_mode():
    """Three pairs, one level, two candidates: the first collapses under pair 0 by a story's
    drift and under pair 2 by the isolator's capacity; the second stands."""
    shape = (3, 1, 2)
    peaks = {name: np.zeros(shape, bool) for name in FLAGS}
    peaks.update(peak_floor_accel=np.ones(shape), crushed=np.zeros(shape, bool),
                 n_impacts=np.zeros(shape, np.int64), collapse_mode=np.zeros(shape, np.int8))
    peaks["collapse_mode"][[0, 2], 0, 0] = [1, 2]
    peaks["invalid_collapse"] = peaks["collapse_mode"] != 0
    stats = search.statistics(peaks, np.ones(3))
    assert stats["n_invalid_collapse"].tolist() == [[2, 0]]
    assert stats["n_invalid_collapse_by_mode"].tolist() == [[[1, 0]], [[1, 0]], [[0, 0]]]


def test_weighted_statistics():
    values = np.array([[1.0], [2.0], [3.0], [4.0]])
    # equal weights: Hazen's plotting positions (i - 1/2) / n, interpolated
    assert weighted_quantiles(values, np.ones(4), [0.5])[0, 0] == 2.5
    assert weighted_quantiles(values, np.ones(4), [0.125, 0.875])[:, 0].tolist() == \
        [1.0, 4.0]
    # weights 1, 3, 1, 1: the steps' midpoints 0.5/6, 2.5/6, 4.5/6, 5.5/6, interpolated
    assert weighted_quantiles(values, [1, 3, 1, 1], [2.5 / 6, 0.5])[:, 0] == \
        pytest.approx([2.0, 2.25])
    assert search.weighted_fraction([[True], [False], [True], [False]],
                                    [1, 3, 1, 1])[0] == pytest.approx(2 / 6)
