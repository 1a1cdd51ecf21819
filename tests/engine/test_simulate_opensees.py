"""Cross-validation against OpenSeesPy, an implementation nobody here wrote.

Same building, real records: no pounding, elastic contact (ElasticPPGap vs the linear law with
COR = 1), JankowskiImpact (vs the Jankowski law) and Hertzdamp (vs the Hertzdamp law), on each
record's first 15 s (tests.helpers.strong_part: the kernel's peaks and impact counts there are
those of the whole record, checked on every run; OpenSees' too, to the last bit, measured on
every case here). These must run in CI, never skip. Tolerances (opensees_reference.AGREEMENT,
which the benchmark quotes too): the worst deviation measured plus a margin. The compiled loop
is checked here; the NumPy loop gives its numbers to 1e-9 on every law
(tests/engine/loops/test_numba_loop.py).
"""
import numpy as np
import pytest

import engine
from engine import Contact
from tests.helpers import strong_part
from tests.reference.opensees_reference import AGREEMENT, opensees_peaks

BETA = 2.75e10  # N/m^1.5: about as stiff as 2500 kN/mm at 1 m/s impacts
CASES = {
    "none": (lambda gap: Contact.none(1), lambda gap: {}),
    "elastic": (lambda gap: Contact.linear(gap, k=2.5e9, cor=1.0),
                lambda gap: dict(contact="elastic", gap=gap, k=2.5e9)),
    "jankowski": (lambda gap: Contact.jankowski(gap, beta=BETA, cor=0.5),
                  lambda gap: dict(contact="jankowski", gap=gap, beta=BETA, cor=0.5)),
    "hertzdamp": (lambda gap: Contact.hertzdamp(gap, k=BETA, cor=0.5),
                  lambda gap: dict(contact="hertzdamp", gap=gap, k=BETA, cor=0.5)),
}
# Gaps about 12-25% below each record's unconstrained peak isolator displacement.
RECORDS = {"olive_view": 0.13, "pacoima": 0.20}


@pytest.fixture(scope="module", params=sorted(RECORDS))
def engine_run(request, paper_record, backend="numba"):
    key = request.param
    gap = RECORDS[key]
    contact = Contact.concat([make(gap) for make, _ in CASES.values()])
    record = paper_record(key)
    assert record.found_in != "stand-in"
    record = strong_part(record, contact)  # OpenSees runs the same part
    return record, gap, engine.simulate(record.accel, record.dt, contact, backend=backend)


@pytest.mark.parametrize("case", list(CASES))
def test_engine_matches_opensees(engine_run, case):
    record, gap, result = engine_run
    member = list(CASES).index(case)
    reference = opensees_peaks(record.accel, record.dt, dt=5e-4, **CASES[case][1](gap))
    if case != "none":
        assert reference["n_impacts"] > 0, "the case must really pound"
    assert result.n_impacts[member] == reference["n_impacts"]
    for name in ("peak_total_accel", "peak_interstory_drift", "peak_isolator_disp",
                 "max_indentation", "max_impact_force"):
        np.testing.assert_allclose(getattr(result, name)[member], reference[name],
                                   rtol=AGREEMENT[case], atol=1e-12, err_msg=name)
