"""The collapses counted by mode (pipeline.assess.collapse_modes), on hand-made codes."""
import numpy as np
import pytest

from engine.results import COLLAPSE_MODES, MODE
from pipeline.assess.collapse_modes import MODES, collapse_numbers, collapse_text, mode_counts

# 2 records x 3 levels: 0 none, 1 story drift, 2 isolator capacity, 3 numerical instability
CODES = np.array([[0, 1, 1],
                  [2, 1, 3]], dtype=np.int8)


def test_the_modes_are_the_engines_less_none():
    assert MODES == COLLAPSE_MODES[1:] == ("story_drift", "isolator_capacity",
                                           "numerical_instability")
    assert [MODES.index(m) + 1 for m in MODES] == [MODE.story_drift, MODE.isolator_capacity,
                                                   MODE.numerical_instability]


def test_counts_by_mode_over_every_run_and_along_an_axis():
    assert mode_counts(CODES).tolist() == [3, 1, 1]
    # over the records (axis 0): per level, one row per mode
    assert mode_counts(CODES, axis=0).tolist() == [[0, 2, 1], [1, 0, 0], [0, 0, 1]]
    assert mode_counts(CODES, axis=1).tolist() == [[2, 1], [0, 1], [0, 1]]
    assert mode_counts(np.zeros((0, 3), np.int8), axis=0).tolist() == [[0] * 3] * 3
    with pytest.raises(ValueError, match="codes are 0 to 3"):
        mode_counts([0, 4])


def test_numbers_and_text():
    numbers = collapse_numbers(CODES)
    assert numbers == {"collapsed": 5, "story_drift": 3, "isolator_capacity": 1,
                       "numerical_instability": 1}
    assert collapse_text(numbers) == ("5 collapsed (3 story drift, 1 isolator capacity, "
                                      "1 numerical instability)")
    assert collapse_text(collapse_numbers(np.zeros(4, np.int8))) == (
        "0 collapsed (0 story drift, 0 isolator capacity, 0 numerical instability)")
