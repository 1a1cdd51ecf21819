"""The packed arrays' declarations (engine/layout.py, engine/loops/layout.py) and the impact
laws' rows: every name a column of something real, every row read by the name it was packed
under."""
import dataclasses

import numpy as np
import pytest

from engine import Building, Isolator
from engine.building import building_arrays
from engine.impact.contact import Contact, law_arguments, law_rows
from engine.impact.registry import LAW_MODULES, ROW_WIDTH
from engine.isolators.registry import LAWS as ISOLATOR_LAWS
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


@pytest.mark.parametrize("law", list(ISOLATOR_LAWS.values()), ids=lambda m: m.NAME)
def test_an_isolator_row_holds_its_law_by_name_and_a_bearing_its_share(law):
    """isolator_rows packs each member's ROW as its law (arrays.isolator_code) declares it
    (fields by name), zero beyond; with n bearings the CARRIED columns are 1/n, the others
    unchanged."""
    iso = {"bilinear": Isolator.bilinear(), "friction_pendulum": Isolator.friction_pendulum(
        radius=2.0, mu_slow=0.05, mu_fast=0.1, rate=30.0),
           "triple_friction_pendulum": Isolator.triple_friction_pendulum(
        L1=0.3, L2=2.0, L3=2.0, d1=0.05, d2=0.3, d3=0.3, mu1=0.02, mu2=0.04, mu3=0.08)}[law.NAME]
    building = Building(isolator=iso)
    arrays = building_arrays([Building(), building], 2)
    rows = layout.isolator_rows(arrays)
    assert arrays.isolator_code[1] == list(ISOLATOR_LAWS).index(law.NAME)
    fields = iso.fields(building.total_mass, building.g)
    assert list(fields) == list(law.ROW._fields)
    assert rows.shape == (2, layout.ISOLATOR_FIELDS)
    assert np.all(rows[1, len(law.ROW):] == 0.0)
    for name, value in fields.items():
        assert rows[1, getattr(law.ROW, name)] == value
    shared = layout.isolator_rows(arrays, bearings=4)
    for name, value in fields.items():
        expected = value / 4 if name in law.CARRIED else value
        assert shared[1, getattr(law.ROW, name)] == expected
    assert set(law.CARRIED) <= set(law.ROW._fields)


def test_the_scalar_peaks_are_the_results_declarations():
    declared = {q.name for q in (*PEAKS, *PLAN_PEAKS, *TORSION_PEAKS)}
    for peaks in (layout.PLANAR_PEAK_COLUMNS, layout.PLAN_PEAK_COLUMNS,
                  layout.TORSION_PEAK_COLUMNS):
        assert set(peaks._fields) <= declared
    assert layout.PLANAR_PEAK_COLUMNS._fields == (
        "peak_isolator_disp", "max_indentation", "max_impact_force", "impact_energy",
        "peak_isolator_force")
    assert set(layout.SQUARED) == {
        "peak_total_accel", "peak_interstory_drift", "peak_isolator_disp",
        "peak_isolator_force", "peak_story_shear", "peak_floor_velocity",
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


def test_the_story_state_is_as_wide_as_the_batchs_widest_story_law():
    from engine import Stories
    from engine.building import distinct_members
    from engine.stories.registry import LAWS as STORY_LAWS

    yields = (2.5e6, 2.2e6, 1.7e6, 1.0e6)
    linear, bilinear = Building(), Building(stories=Stories.bilinear(yield_force=yields))
    imk = Building(stories=Stories.imk(yield_force=yields, plastic_deformation=0.03,
                                       post_capping_deformation=0.3))
    for members, width in (([linear] * 3, 1), ([linear, bilinear, linear], 2),
                           ([bilinear, imk, linear], STORY_LAWS["imk"].N_STATE)):
        arrays = building_arrays(members, len(members))
        first, _ = distinct_members(arrays.distinct)
        state = layout.story_states(arrays, first)
        assert state.shape == (3, 4, width) and state.flags.c_contiguous and state.flags.writeable
        np.testing.assert_array_equal(state, arrays.story_state[:, :, :width])
        assert not arrays.story_state[:, :, width:].any()  # what was left out is unused
        in_plan = layout.story_states(arrays, first, 2)
        assert in_plan.shape == (3, 4, 2, width)
        np.testing.assert_array_equal(in_plan[:, :, 1], state)
