"""The derived responses (pipeline.assess.derived) against hand computations on small arrays,
"crushed"
at, below and above the limit as the bumper law has it, and the declarations complete."""
import numpy as np
import pytest

from engine.impact.laws import rubber_bumper
from engine.results import Result
from pipeline.assess import derived, validity


def test_largest_floor_accel_and_story_drift_over_the_last_axis():
    accel = np.array([[1.0, 3.0, 2.0], [4.0, 0.5, 0.5]])  # (members, levels), base first
    assert derived.largest_floor_accel(accel).tolist() == [3.0, 4.0]
    stacked = np.stack([accel, accel[::-1]])  # (2, 2, levels): any leading axes
    assert derived.largest_floor_accel(stacked).tolist() == [[3.0, 4.0], [4.0, 3.0]]
    drift = np.array([[0.01, 0.02], [0.03, 0.0]])  # (members, stories)
    assert derived.largest_story_drift(drift).tolist() == [0.02, 0.03]


def test_bumper_stress_shares_the_force_among_the_bumpers():
    # 900 kN on 4 bumpers of 150 x 150 mm: 900e3 / (4 x 0.0225) = 10 MPa
    assert derived.bumper_stress(900e3, 4, 0.0225) == pytest.approx(10e6, rel=1e-15)
    got = derived.bumper_stress(np.array([[900e3], [0.0]]), np.array([4, 8]), 0.0225)
    np.testing.assert_allclose(got, [[10e6, 5e6], [0.0, 0.0]], rtol=1e-15)
    assert validity.bumper_stress is derived.bumper_stress  # one definition


def test_crushed_strictly_beyond_delta_u_as_the_bumper_law_has_it():
    delta_u = 0.04
    below, at, above = np.nextafter(delta_u, 0), delta_u, np.nextafter(delta_u, 1)
    assert derived.crushed([below, at, above], delta_u).tolist() == [False, False, True]
    # the law: the wall behind the rubber, k_w (delta - delta_u), acts only beyond delta_u
    indentation = np.array([below, at, above, 0.05])
    row = {"k": 0.0, "n": 2.65, "delta_u": delta_u, "k_w": 1.5e9, "c_imp_coef": 0.0,
           "c_imp_exponent": 1.0}
    wall, _ = rubber_bumper.force_terms(indentation, 1.0, 1.0,
                                        tuple(row[name] for name in rubber_bumper.ROW._fields))
    np.testing.assert_array_equal(derived.crushed(indentation, delta_u), wall > 0)
    # per member: each against its own limit
    assert derived.crushed([0.03, 0.03], [0.02, 0.04]).tolist() == [True, False]


def _result() -> Result:
    """Two members of a 3-level building, peaks by hand."""
    return Result(peak_total_accel=np.array([[1.0, 3.0, 2.0], [4.0, 0.5, 0.5]]),
                  peak_interstory_drift=np.array([[0.01, 0.02], [0.03, 0.0]]),
                  peak_isolator_disp=np.array([0.2, 0.3]),
                  max_indentation=np.array([0.01, 0.05]),
                  max_impact_force=np.array([900e3, 1.8e6]),
                  n_impacts=np.array([1, 2]), impact_energy=np.zeros(2),
                  peak_isolator_force=np.array([2e6, 3e6]),
                  peak_story_shear=np.array([[4e6, 2e6], [5e6, 1e6]]),
                  peak_floor_velocity=np.array([[0.5, 0.6, 0.7], [0.8, 0.9, 1.0]]),
                  residual_isolator_disp=np.array([0.01, 0.0]),
                  residual_interstory_drift=np.zeros((2, 2)), dt=1e-3)


def test_declarations_read_an_engine_result_or_a_dict_of_peaks():
    result = _result()
    expected = {"peak_floor_accel": [3.0, 4.0], "peak_story_drift": [0.02, 0.03],
                "bumper_stress": [10e6, 20e6], "crushed": [False, True]}
    for peaks in (result, result.peaks()):
        got = derived.derive(peaks, n_bumpers=4, area=0.0225, delta_u=0.04)
        assert list(got) == list(derived.DERIVED)
        for name, values in expected.items():
            np.testing.assert_allclose(got[name], values, rtol=1e-15, err_msg=name)
    # without the bumpers' parameters: only what needs none
    assert list(derived.derive(result)) == ["peak_floor_accel", "peak_story_drift"]
    assert derived.quantity("crushed")(result, delta_u=0.005).tolist() == [True, True]
    with pytest.raises(TypeError, match="n_bumpers, area"):
        derived.quantity("bumper_stress")(result)


def test_every_declaration_has_units_and_a_long_name():
    assert set(derived.DERIVED) == {"peak_floor_accel", "peak_story_drift", "bumper_stress",
                                    "crushed"}
    for name, q in derived.DERIVED.items():
        assert q.name == name and derived.quantity(name) is q
        assert q.units and q.long_name and "{" not in q.long_name, name
    assert derived.quantity("peak_floor_accel").units == "m s-2"
    assert derived.quantity("bumper_stress").units == "Pa"
    stress = derived.quantity("bumper_stress")
    assert stress.long_name == "mean contact stress on each bumper at the largest impact force"
    assert stress.describe(each="each bumper (22500 mm2)") == (
        "mean contact stress on each bumper (22500 mm2) at the largest impact force")
    with pytest.raises(KeyError, match="peak_floor_accel"):
        derived.quantity("peak_floor_acceleration")
