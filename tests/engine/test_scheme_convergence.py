"""dt convergence on the paper's practical example (section 4, SPEC section 4): halving the
default step moves every peak by less than 0.5%. This is how DEFAULT_DT was chosen. On the
compiled loop: the NumPy loop gives its numbers to 1e-9 (tests/engine/loops/test_numba_loop.py),
so its convergence is the same."""
import numpy as np
import pytest

import engine
from engine import Contact
from tests.helpers import strong_motion

PRACTICAL_EXAMPLE = {"kobe": 0.15, "pacoima": 0.24}  # m, the paper's gaps
PEAKS = ("peak_total_accel", "peak_interstory_drift", "peak_isolator_disp", "max_indentation",
         "max_impact_force")


@pytest.mark.parametrize("key", sorted(PRACTICAL_EXAMPLE))
def test_halving_the_default_dt_moves_peaks_less_than_half_a_percent(real_paper_record, key,
                                                                     backend="numba"):
    gap = PRACTICAL_EXAMPLE[key]
    # No poundings, no bumpers (linear wall at the gap), 4 bumpers of 5 cm (gap - 5 cm).
    contact = Contact.concat([Contact.none(1), Contact.linear(gap), Contact.bumper(gap)])
    record = strong_motion(real_paper_record(key), backend, contact)
    dt = engine.DEFAULT_DT
    coarse = engine.simulate(record.accel, record.dt, contact, dt=dt, backend=backend)
    fine = engine.simulate(record.accel, record.dt, contact, dt=dt / 2, backend=backend)
    assert np.all(coarse.n_impacts[1:] > 0)
    np.testing.assert_array_equal(coarse.n_impacts, fine.n_impacts)
    for name in PEAKS:
        np.testing.assert_allclose(getattr(coarse, name), getattr(fine, name), rtol=5e-3,
                                   err_msg=name)
