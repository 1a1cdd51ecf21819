"""Batches (pipeline/execute/batches.py): the batch size changes no number, and each member is
simulated once (the baseline once per record and gap)."""

import pytest

import pipeline
from tests.pipeline.small_sweep import (
    RECORDS,
    SMALL,
    assert_same_archive,
)

# --------------------------------------------------------------------------- bitwise identity


@pytest.mark.parametrize("batch_size", [1, 7, 10_000])
def test_batch_size_does_not_change_results(reference, batch_size, count_simulated):
    ds = pipeline.sweep(RECORDS, **SMALL, workers=1, baseline=True, unconstrained=True,
                        batch_size=batch_size, quiet=True)
    assert_same_archive(ds, reference)
    members = 3 * 2 + 3 + 1  # grid + baseline per gap + unconstrained, per record
    assert max(count_simulated) == min(batch_size, members)
    assert sum(count_simulated) == 2 * members  # baseline computed once per (record, gap)
