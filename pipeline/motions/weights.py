"""The weights of a suite's records that keep one earthquake from dominating what they say:
records of one earthquake share its weight (FEMA P695 keeps at most two per earthquake;
weighting keeps them all). Read by the code suites here and by every statistic of
pipeline.assess (fragility fits, outcome counts)."""
from __future__ import annotations

import numpy as np


def event_weights(event_ids) -> np.ndarray:
    """(R,) record weights so that every earthquake counts equally, from event_ids (R,) (any
    hashable labels, e.g. earthquake names or ids; records of one earthquake share one).

    w_i = 1 / (records sharing record i's earthquake), normalised to sum to R: each of the E
    earthquakes weighs R / E in total, and the weights keep the scale of unit weights (the
    counts of fit_stripes stay comparable to numbers of records). FEMA P695 limits its record
    sets to two records per earthquake so that no event dominates; weighting keeps all the
    records instead. The fits are then weighted pseudo-likelihoods (see fit_stripes).
    """
    ids = np.asarray(event_ids)
    if ids.ndim != 1:
        raise ValueError(f"event_ids must be 1-D, got shape {ids.shape}")
    _, inverse, counts = np.unique(ids, return_inverse=True, return_counts=True)
    w = 1.0 / counts[inverse.ravel()]
    return w * (ids.size / np.sum(w))
