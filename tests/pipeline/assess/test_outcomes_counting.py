"""pipeline.assess.outcomes.count: one way to count a claim, on hand-made datasets for every
quantifier. Cases are (pair, ...): the claim holds, it applies (contact), it changed beyond
the tolerance (a tie where not); each pair carries its earthquake's weight once."""
import numpy as np
import pytest

from pipeline.assess.outcomes import ALMOST_EVERY, QUANTIFIERS, count, judged

T, F = True, False


def test_ties_are_outside_the_denominator_and_reported_beside():
    # one pair, four cases: 2 held, 1 failed, 1 tie (applies, not changed)
    c = count("most", [[T, T, F, F]], [[T, T, T, T]], [[T, T, T, F]])
    assert (c.held_cases, c.counted_cases, c.tie_cases) == (2, 3, 1)
    assert c.fraction == pytest.approx(2 / 3) and c.verdict is True
    # counted as a failure, the tie would make it 2 of 4: not "most"
    assert judged("most", 2, 4) is False
    # a pair with only ties: its weight is in `ties`, not in the denominator
    c = count("most", [[F, F], [T, T]], [[T, T], [T, T]], [[F, F], [T, T]])
    assert (c.held, c.counted, c.ties, c.not_counted) == (1.0, 1.0, 1.0, 0.0)
    assert c.pairs == 1 and c.verdict is True


def test_no_contact_is_outside_the_denominator_and_reported_beside():
    holds = [[T, F, F], [F, F, F]]
    applies = [[T, F, F], [F, F, F]]  # pair 1 never touches
    c = count("every", holds, applies)
    assert c.verdict is True and c.counted == 1.0 and c.not_counted == 1.0
    assert c.not_counted_cases == 5 and c.counted_cases == 1
    assert "5 where it does not apply (weight 1)" in c.text()
    # nothing applies: not tested, whatever the quantifier
    for q in QUANTIFIERS:
        assert count(q, holds, np.zeros((2, 3), bool)).verdict is None


def test_a_pair_at_twelve_angles_weighs_as_one_earthquake():
    # pair 0 holds at all 12 angles, pair 1 (another earthquake) fails at its 1 counted angle
    holds = np.zeros((2, 12), bool)
    holds[0] = True
    applies = np.zeros((2, 12), bool)
    applies[0], applies[1, 0] = True, True
    c = count("most", holds, applies, events=["Kobe", "Northridge"])
    assert (c.held_cases, c.counted_cases) == (12, 13)  # 12 of 13 cases...
    assert c.fraction == pytest.approx(0.5)  # ...but one earthquake of two
    assert c.verdict is False and c.events == 2 and c.pairs == 2
    # a pair's share: the fraction of its counted cases that hold, times its weight
    holds[0, :3] = False
    c = count("most", holds, applies, weights=[1.0, 1.0])
    assert c.held == pytest.approx(9 / 12) and c.counted == 2.0


def test_two_pairs_of_one_earthquake_share_its_weight():
    # pairs 0 and 1: Northridge, both fail; pair 2: Kobe, holds
    holds, applies = [[F], [F], [T]], [[T], [T], [T]]
    c = count("most", holds, applies, events=["Northridge", "Northridge", "Kobe"])
    assert c.fraction == pytest.approx(0.5)  # not 1/3: each earthquake once
    assert c.verdict is False and c.events == 2 and c.pairs == 3
    # without earthquake ids every pair weighs the same: 1/3
    assert count("most", holds, applies).fraction == pytest.approx(1 / 3)
    # given weights (e.g. a suite's record_weight, already per earthquake) are used as they are
    c = count("most", holds, applies, weights=[0.5, 0.5, 1.0])
    assert c.fraction == pytest.approx(0.5)


def test_may_agrees_with_one_held_case():
    holds = np.zeros((5, 4), bool)
    applies = np.ones((5, 4), bool)
    holds[3, 2] = True
    for wording in ("may", "can", "some"):
        c = count(wording, holds, applies)
        assert c.verdict is True and c.quantifier == "some" and c.wording == wording
    assert count("may", np.zeros((5, 4), bool), applies).verdict is False
    # a "held" case that is a tie does not count: it did not change
    changed = np.ones((5, 4), bool)
    changed[3, 2] = False
    assert count("may", holds, applies, changed).verdict is False


def test_every_differs_with_one_counted_failure_and_ignores_ties():
    holds = np.ones((3, 2, 2), bool)  # (pair, level, gap)
    applies = np.ones((3, 2, 2), bool)
    changed = np.ones((3, 2, 2), bool)
    holds[1, 0, 1] = False
    assert count("every", holds, applies, changed).verdict is False
    assert count("all", holds, applies, changed).verdict is False
    changed[1, 0, 1] = False  # the same case within the tolerance: a tie, ignored
    c = count("every", holds, applies, changed)
    assert c.verdict is True and c.tie_cases == 1 and c.fraction == 1.0
    applies[1, 0, 1], changed[1, 0, 1] = False, True  # or no contact there: ignored too
    assert count("every", holds, applies, changed).verdict is True


def test_most_and_almost_every_on_weights():
    # ten pairs of ten earthquakes, one case each
    applies = np.ones((10, 1), bool)
    for n_held, most, almost in ((5, False, False), (6, True, False), (9, True, True),
                                 (10, True, True)):
        holds = (np.arange(10) < n_held)[:, None]
        assert count("most", holds, applies).verdict is most
        assert count("almost all", holds, applies).verdict is almost
        assert count("almost every", holds, applies).verdict is almost
    assert ALMOST_EVERY == 0.9
    # ties of pairs 8 and 9: 8 of 8 counted, "almost every" holds
    holds = (np.arange(10) < 8)[:, None]
    changed = holds.copy()
    c = count("almost every", holds, applies, changed)
    assert c.verdict is True and c.ties == 2.0 and c.counted == 8.0


def test_weights_partition_and_numbers():
    holds = [[T, F], [F, F], [F, F]]
    applies = [[T, T], [T, F], [F, F]]
    changed = [[T, T], [F, T], [T, T]]
    c = count("most", holds, applies, changed, weights=[2.0, 1.0, 0.5])
    assert c.held + (c.counted - c.held) + c.ties + c.not_counted == pytest.approx(3.5)
    assert (c.counted, c.ties, c.not_counted) == (2.0, 1.0, 0.5)
    n = c.numbers()
    assert n["held_weight"] == pytest.approx(1.0) and n["failed_cases"] == 1
    assert n["verdict"] is False  # 1.0 of 2.0 is not more than half
    with pytest.raises(ValueError):
        count("usually", holds, applies)


def test_configurations_compared_by_fits_count_as_one_set_of_cases():
    """The fragility and loss verdicts compare configurations whose values pool every pair
    (fits, decision-table medians): one set of cases, no weights to state."""
    holds = np.array([[True, False, False, False]])
    applies = np.array([[True, True, True, False]])
    changed = np.array([[True, True, False, True]])
    c = count("can", holds, applies, changed)
    assert c.verdict is True and (c.held_cases, c.counted_cases, c.tie_cases) == (1, 2, 1)
    assert c.text("configurations") == (
        "holds in 1 of 2 configurations; beside, not counted: 1 within the 2% tolerance, 1 "
        "where it does not apply")
    assert count("can", holds, np.zeros_like(applies)).verdict is None
