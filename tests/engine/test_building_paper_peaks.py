"""The paper's unconstrained peak isolator displacements (sections 4 and 5.6), on the compiled
loop (the NumPy loop gives its numbers to 1e-9: tests/engine/loops/test_numba_loop.py)."""
import pytest

import engine
from tests.helpers import strong_motion

# The paper's value (cm) and this engine's measured excess over it, pinned to +-0.3 points.
# Kobe is 9.4% over: the paper used an older PEER version of the record (0.821 g, ours 0.834
# g); the others 2.3-3.4% (record versions and the unstated damping details, SPEC section 1).
PAPER = {"kobe": (16.74, 0.0938), "olive_view": (15.63, 0.0228), "pacoima": (26.8, 0.0338),
         "sylmar_converter": (31.7, 0.0342)}
MARGIN = 0.003


@pytest.mark.parametrize("key", sorted(PAPER))
def test_unconstrained_peak_isolator_displacement(real_paper_record, key, backend="numba"):
    record = strong_motion(real_paper_record(key), backend, engine.Contact.none(1))
    result = engine.simulate(record.accel, record.dt, engine.Contact.none(1), backend=backend)
    paper_cm, excess = PAPER[key]
    assert result.peak_isolator_disp[0] * 100 / paper_cm - 1 == pytest.approx(excess,
                                                                              abs=MARGIN)
