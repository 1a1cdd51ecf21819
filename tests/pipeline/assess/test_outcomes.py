"""The counting of comparisons (pipeline.assess.outcomes): effects, quantiles and quantifiers.
(Counting a claim over pairs and their weights: test_outcomes_counting.py.)"""
import numpy as np
import pytest

from pipeline.assess import outcomes


def test_quantiles_are_the_median_and_one_sigma_either_side():
    assert outcomes.QUANTILES == (0.16, 0.5, 0.84)


def test_effect_counts_ties_as_neutral_and_only_where_contact():
    with_b = np.array([0.5, 1.0, 1.01, 1.5, 2.0, 1.0])
    without = np.array([1.0, 1.0, 1.0, 1.0, 1.0, 1.0])
    e = outcomes.effect(with_b, without)
    assert e.tolist() == [-1, 0, 0, 1, 1, 0]
    counted = outcomes.where_contact([1, 1, 0, 2, 0, 0], [0, 3, 1, 0, 2, 0])
    assert counted.tolist() == [True, True, True, True, True, False]
    t = outcomes.tally(e, counted)
    assert t == {"helped": 1, "neutral": 2, "hurt": 2, "counted": 5, "no_contact": 1}
    t = outcomes.tally(e, counted, weights=[0.5, 1, 1, 1, 1, 1])
    assert t["helped"] == 0.5 and t["counted"] == 4.5


def test_quantifiers():
    assert outcomes.judged("every", 5, 5) and not outcomes.judged("every", 4, 5)
    assert outcomes.judged("most", 3, 5) and not outcomes.judged("most", 2, 4)
    assert outcomes.judged("some", 1, 9) and not outcomes.judged("some", 0, 9)
    assert outcomes.judged("most", 0, 0) is None
    with pytest.raises(ValueError):
        outcomes.judged("nearly", 1, 1)  # the paper's words are known; others refused
