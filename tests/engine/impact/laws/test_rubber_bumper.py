"""The bumper law with the pad's shape (issue 27, point 7): Eq. 11 scaled by Gent & Lindley's
compression modulus ratio (1 + 2 k S^2) / (1 + 2 k S_cal^2), exact where it must be; the
damping calibration unchanged; the flags past the calibration's stress and strain; the design
search's use of it."""
import numpy as np
import pytest

import engine
from engine import Contact, units
from engine.impact.laws import rubber_bumper
from engine.impact.laws.rubber_bumper import GENT_LINDLEY_K
from pipeline.assess import validity

LAW = rubber_bumper.PARAMETERS
K_R, N, ALPHA = LAW.k_r.default, LAW.n.default, LAW.alpha.default


def eq11(area, t, count=1):
    """Eq. 11-12 as the law had them before the shape: alpha count A K_r / t^n, N/m^n."""
    return ALPHA * count * (area * K_R / np.asarray(t, dtype=float) ** N)


def test_calibration_pads_keep_todays_stiffness_exactly():
    # the paper's bumper (S 0.75) and every recipe's pad at the default (no shape effect)
    for area, t, count in ((0.150**2, 0.05, 4), (0.040**2, 0.010, 1), (1.0, 0.20, 1)):
        assert Contact.bumper(1.0, thickness=t, area=area, n_bumpers=count).k[0] \
            == eq11(area, t, count)
        assert rubber_bumper.impact_stiffness(area, t, count=count) == eq11(area, t, count)
    # the pad K_r was fitted on (Kajita et al., 40 x 40 x 10 mm, S 1.0): exactly Eq. 11 for
    # any k, and its published 0.2 and 0.45 kN/mm^2.65
    kajita = 0.040**2, 0.010
    assert rubber_bumper.shape_factor(*kajita) == LAW.shape_factor_cal.default == 1.0
    for k in (GENT_LINDLEY_K, 0.54, 0.3):
        assert rubber_bumper.shape_ratio(*kajita, k) == 1.0
        assert Contact.bumper(1.0, thickness=0.010, area=kajita[0], n_bumpers=1,
                              shape_k=k).k[0] == eq11(*kajita)
    to_kn_mm = units.kn_per_mm_n(N)
    assert rubber_bumper.static_stiffness(*kajita, shape_k=1.0) / to_kn_mm == pytest.approx(
        0.2, rel=1e-3)
    assert rubber_bumper.impact_stiffness(*kajita, shape_k=1.0) / to_kn_mm == pytest.approx(
        0.45, rel=1e-3)
    # k = 0 is the paper's Eq. 11 whatever the shape: the ratio is exactly 1
    assert rubber_bumper.compression_ratio(np.array([0.3, 0.75, 2.0]), 0.0).tolist() == [1.0] * 3


@pytest.mark.parametrize("side, t, k", [(0.10, 0.05, 1.0), (0.15, 0.05, 1.0),
                                        (0.30, 0.05, 1.0), (0.224, 0.112, 0.54)])
def test_other_shapes_take_gent_and_lindleys_ratio(side, t, k):
    s = side / (4 * t)
    expected = (1 + 2 * k * s**2) / (1 + 2 * k * 1.0**2)
    shaped = Contact.bumper(1.0, thickness=t, area=side**2, n_bumpers=2, shape_k=k).k[0]
    assert shaped / eq11(side**2, t, 2) == pytest.approx(expected, rel=1e-12)
    assert rubber_bumper.shape_factor(side**2, t) == pytest.approx(s, rel=1e-12)


def test_named_ratios():
    # the design pads (22.4 cm square, 11.2 cm thick, S 0.5): half Eq. 11 at k = 1;
    # the paper's bumper (S 0.75): 2.125 / 3; a pad of S 1.5: 5.5 / 3
    assert rubber_bumper.shape_ratio(0.224**2, 0.112, 1.0) == pytest.approx(0.5, rel=1e-12)
    assert rubber_bumper.shape_ratio(0.150**2, 0.05, 1.0) == pytest.approx(2.125 / 3)
    assert rubber_bumper.compression_ratio(1.5, 1.0) == pytest.approx(5.5 / 3)
    # the calibration pad's shape is a declared parameter: a rubber fitted on another pad
    assert rubber_bumper.compression_ratio(0.75, 1.0, shape_factor_cal=0.75) == 1.0


# The compiled loop: the NumPy loop gives engine.two_body's numbers to 1e-9 for the bumper law,
# whose shape correction sets its stiffness before the loop runs
# (tests/engine/loops/test_numba_loop.py::test_two_body_backends_agree).
@pytest.mark.parametrize("backend", ["numba"])
def test_shape_corrected_pad_realises_the_same_cor(backend):
    """The damping calibration holds with the shape: the COR of a pure power law with C_imp =
    c / v_imp^e does not depend on its stiffness, so a pad of S 0.5 (half Eq. 11's k) and one
    of S 1.5 realise the COR of the uncorrected pad, Eq. 9's and the calibrated rule's alike."""
    m = 300.0
    cor = np.array([0.3, 0.45, 0.7, 0.9])
    v = 1.0
    for rule, tolerance in (("eq9", 0.03), ("calibrated", 1e-3)):
        got = []
        for side, k in ((0.10, 0.0), (0.10, 1.0), (0.30, 1.0)):  # t 5 cm: S 0.5, 0.5, 1.5
            contact = Contact.bumper(1.0, thickness=0.05, area=side**2, n_bumpers=4,
                                     cor=cor, m_eff=m / 2, shape_k=k, c_imp_rule=rule)
            res = engine.two_body(m, m, v, contact, backend=backend)
            assert np.all(res.peak_indentation < contact.delta_u)  # the power law only
            got.append(res.cor)
        np.testing.assert_allclose(got[1], got[0], rtol=2e-3)
        np.testing.assert_allclose(got[2], got[0], rtol=2e-3)
        np.testing.assert_allclose(got[1], cor, rtol=tolerance + 0.01)


def test_listed_members_carry_the_shape_to_the_engine():
    """pipeline.listed's columns (LISTED_PARAMS: shape_k, shape_factor_cal) reach the law."""
    from pipeline.grid import contact_for
    from pipeline.members import LISTED_PARAMS, MEMBER_DTYPE

    assert {"shape_k", "shape_factor_cal"} <= set(LISTED_PARAMS)
    members = np.zeros(3, dtype=MEMBER_DTYPE)
    for name in MEMBER_DTYPE.names[1:]:
        members[name] = np.nan
    members["law"] = "bumper"
    members["m_eff"] = LAW.m_eff.default
    for sweep, parameter in LAW.swept().items():
        members[sweep] = parameter.default if sweep != "gap" else 0.3
    members["thickness"] = 0.112
    members["area"] = 0.224**2
    members["shape_k"] = [np.nan, 0.0, 1.0]
    k = contact_for(members).k
    assert k[0] == k[1] == eq11(0.224**2, 0.112, LAW.n_bumpers.default)
    assert k[2] / k[1] == pytest.approx(0.5, rel=1e-12)


# ----------------------------------------------------------------- the calibration's range


def test_flags_past_the_calibrations_strain_and_stress():
    """A hand-made set: 4 bumpers of 150 x 150 x 50 mm; strain max_indentation / t past 0.8 and
    stress force / (n A) past 30.9 MPa flagged, each on its own; none without bumpers."""
    assert validity.RUBBER_STRAIN_LIMIT == 0.8
    assert validity.RUBBER_STRESS_LIMIT == pytest.approx(30.9e6, rel=2e-3)
    t, area, n = 0.05, 0.0225, 4
    on_all = n * area  # m^2
    accel = np.ones((5, 2))
    drift = np.zeros((5, 1))
    indentation = np.array([0.039, 0.041, 0.039, 0.041, 0.0])
    force = np.array([30e6, 30e6, 31e6, 31e6, 0.0]) * on_all
    got = validity.flags(accel, drift, force, [1e9], validity.Limits(), n_bumpers=n,
                         area=area, max_indentation=indentation, thickness=t)
    assert got["invalid_bumper_strain"].tolist() == [False, True, False, True, False]
    assert got["invalid_bumper_stress"].tolist() == [False, False, True, True, False]
    # the strain of the law's own numbers: at 0.8 t exactly, not past it
    assert not validity.flags(accel[:1], drift[:1], force[:1], [1e9], validity.Limits(),
                              n_bumpers=n, area=area, max_indentation=[0.8 * t],
                              thickness=t)["invalid_bumper_strain"][0]
    # members without bumpers (n inf, the studies' convention) and runs without thickness:
    # not flagged
    bare = validity.flags(accel, drift, force, [1e9], validity.Limits(),
                          n_bumpers=np.full(5, np.inf), area=1.0, max_indentation=indentation,
                          thickness=t)
    assert not bare["invalid_bumper_strain"].any()
    unchecked = validity.flags(accel, drift, force, [1e9], validity.Limits(), n_bumpers=n,
                               area=area)
    assert not unchecked["invalid_bumper_strain"].any()
    # flags_of reads max_indentation from the peaks; a limit of the user's own
    peaks = {"peak_total_accel": np.ones((2, 5)), "peak_interstory_drift": np.zeros((2, 4)),
             "max_impact_force": np.zeros(2), "max_indentation": np.array([0.03, 0.035])}
    looser = validity.flags_of(peaks, engine.Building(), validity.Limits(bumper_strain=0.65),
                               n_bumpers=n, area=area, thickness=t)
    assert looser["invalid_bumper_strain"].tolist() == [False, True]
    assert "bumper strain 0.8" in validity.Limits().describe()
    assert list(validity.FLAGS)[:2] == ["invalid_bumper_stress", "invalid_bumper_strain"]


# ------------------------------------------------------------------------- the design search


def test_design_search_uses_the_shape():
    from studies.design import search, space

    # the usable strain: where alpha K_r rho(S) eps^n reaches 30.9 MPa
    limit = validity.RUBBER_STRESS_LIMIT
    for s, expected in ((0.5, 0.765), (1.0, 0.589), (1.5, 0.469)):
        assert space.usable_strain(0.8, limit, s, 1.0) == pytest.approx(expected, abs=1e-3)
        eps = space.usable_strain(0.8, limit, s, 1.0)
        assert ALPHA * K_R * rubber_bumper.compression_ratio(s, 1.0) * eps**N == \
            pytest.approx(limit, rel=1e-12)
    assert space.usable_strain(0.8, limit, 0.5, 0.0) == space.usable_strain(0.8, limit)
    # the cavity's bound follows the pad's shape, and bounds S from below in turn
    bounds = space.Bounds(gap=0.3, clearance=0.05, wall_length=100.0,
                          usable_strain=lambda s: space.usable_strain(0.8, limit, s, 1.0))
    config = {"thickness": 0.1, "cavity_ratio": 0.4, "n_bumpers": 4, "shape_factor": 1.0,
              "wall_k": 1.5e9}
    limits = bounds.limits(config)
    assert limits["cavity_ratio"][1][0] == pytest.approx(1 - 0.589, abs=1e-3)
    s_min = limits["shape_factor"][0][0]
    assert bounds.usable(s_min) == pytest.approx(0.6, rel=1e-9) and 0.9 < s_min < 1.0
    assert bounds.allows({**config, "shape_factor": s_min})
    assert not bounds.allows({**config, "shape_factor": 0.9})
    assert bounds.least_usable == pytest.approx(0.469, abs=1e-3)
    # the members run with the shape; candidates of equal n x area but other shapes differ
    table = {"thickness": np.array([0.1, 0.1]), "cavity_ratio": np.zeros(2),
             "n_bumpers": np.array([16.0, 4.0]), "shape_factor": np.array([0.5, 1.0]),
             "wall_k": np.full(2, 1.5e9)}
    members = search.bumper_members(table, 0.3, 0.8, shape_k=1.0)
    assert members.columns["shape_k"].tolist() == [1.0, 1.0]
    plain = search.bumper_members(table, 0.3, 0.8)
    np.testing.assert_allclose(members.contact.k / plain.contact.k, [0.5, 1.0], rtol=1e-12)
    assert plain.contact.k[0] == plain.contact.k[1]  # n x area alone, without the shape
    keys = [search._dynamics(space.row(table, i), 1.0) for i in range(2)]
    assert keys[0] != keys[1]
    assert search._dynamics(space.row(table, 0)) [:3] == search._dynamics(space.row(table, 1))[:3]
    assert "S 0.5, k_st 0.5 x Eq. 11's" in search.describe(table, 0, 1.0)


def test_a_wall_holds_its_length_over_two_pad_sides():
    from engine.impact.laws.rubber_bumper import WALL_LENGTH, crowded, most_bumpers

    assert most_bumpers(0.15 ** 2) == 60 == int(WALL_LENGTH / 0.3)  # 2 x 60 x 0.15 m = 18 m
    assert most_bumpers(0.15 ** 2, wall_length=17.99) == 59
    assert crowded({"n_bumpers": np.array([4, 60])}) is None
    assert "give at most 60" in crowded({"n_bumpers": np.array([4, 61])})
    # a listed member's own pads: 100 pads of 60 mm need 12 m, 100 of 150 mm 30 m
    assert crowded({"n_bumpers": np.array([100.0]), "area": np.array([0.06 ** 2])}) is None
    assert "pads of 150 mm" in crowded({"n_bumpers": np.array([4.0, 100.0]),
                                        "area": np.array([0.06 ** 2, np.nan])})


def test_a_refusal_names_the_first_member_that_fails_not_every_member():
    """Bumpers that would close the gap, or a cavity as deep as the pad, are refused in one
    line naming the first such member's values and how many members fail, whatever the
    batch's size."""
    import re

    import numpy as np
    import pytest

    import engine
    from engine.errors import EngineError

    gaps = np.linspace(0.2, 0.01, 100_000)  # the last 20% of the members too close
    with pytest.raises(EngineError) as caught:
        engine.Contact.bumper(gaps, thickness=0.05)
    said = str(caught.value)
    assert "\n" not in said and len(said) < 200
    first = gaps[gaps <= 0.05][0]
    assert re.search(rf"gap {first:g} m, thickness 0.05 m, cavity 0 m \((\d+) of 100000 members\)",
                     said)
    assert f"({np.count_nonzero(gaps <= 0.05)} of 100000 members)" in said
    with pytest.raises(EngineError, match=r"^cavity must be smaller than thickness, got cavity "
                                          r"0\.05 m, thickness 0\.05 m$"):
        engine.Contact.bumper([0.2], thickness=0.05, cavity=0.05)
