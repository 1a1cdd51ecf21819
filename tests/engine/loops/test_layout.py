"""The packed arrays' declarations (engine/layout.py, engine/loops/layout.py) and the impact
laws' rows: every name a column of something real, every row read by the name it was packed
under."""
import dataclasses

import numpy as np
import pytest

from engine.building import BuildingArrays
from engine.impact.contact import Contact, law_arguments, law_rows
from engine.impact.registry import LAW_MODULES, ROW_WIDTH
from engine.layout import appended, columns
from engine.loops import layout
from engine.results import PEAKS, PLAN_PEAKS, TORSION_PEAKS

EXAMPLES = {"linear": Contact.linear(0.1), "jankowski": Contact.jankowski(0.1, beta=2.75e9),
            "hertzdamp": Contact.hertzdamp(0.1, k=2.75e9), "bumper": Contact.bumper(0.1)}


def test_columns_are_numbered_from_their_declaration():
    first = columns("First", "a", "b")
    both = appended("Both", first, "c")
    assert (first.a, first.b, len(first)) == (0, 1, 2)
    assert both._fields == ("a", "b", "c") and both.c == 2


def test_the_isolator_columns_are_building_arrays_fields():
    names = {f.name for f in dataclasses.fields(BuildingArrays)}
    assert set(layout.ISOLATOR._fields) <= names
    for member in (layout.PLANAR, layout.PLAN, layout.TORSION):
        assert member._fields[:len(layout.ISOLATOR)] == layout.ISOLATOR._fields


def test_the_scalar_peaks_are_the_results_declarations():
    declared = {q.name for q in (*PEAKS, *PLAN_PEAKS, *TORSION_PEAKS)}
    for peaks in (layout.PLANAR_PEAK_COLUMNS, layout.PLAN_PEAK_COLUMNS,
                  layout.TORSION_PEAK_COLUMNS):
        assert set(peaks._fields) <= declared
    assert layout.PLANAR_PEAK_COLUMNS._fields == (
        "peak_isolator_disp", "max_indentation", "max_impact_force", "impact_energy")
    assert set(layout.SQUARED) == {
        "peak_total_accel", "peak_interstory_drift", "peak_isolator_disp",
        "peak_total_accel_xy", "peak_interstory_drift_xy", "peak_isolator_disp_xy",
        "peak_corner_disp"}


@pytest.mark.parametrize("law", list(LAW_MODULES.values()), ids=lambda m: m.NAME)
def test_a_law_reads_its_row_by_name(law):
    """The row packed for the compiled loops and the tuple for the NumPy ones hold the law's
    ROW fields, so that its force_terms gives the same numbers on either."""
    contact = EXAMPLES[law.NAME]
    names = {f.name for f in dataclasses.fields(Contact)}
    assert set(law.ROW._fields) <= names and len(law.ROW) <= ROW_WIDTH
    rows = law_rows(contact)
    assert rows.shape == (len(contact), ROW_WIDTH)
    delta, rate, v_imp = np.array([0.004]), np.array([-0.2]), np.array([0.5])
    arrays = law.force_terms(delta, rate, v_imp, law_arguments(contact, law))
    scalars = law.force_terms(delta[0], rate[0], v_imp[0], rows[0])
    for a, s in zip(arrays, scalars, strict=True):
        assert np.asarray(a)[0] == s


def test_a_member_without_wall_has_a_zero_row():
    assert not law_rows(Contact.none(3)).any()
