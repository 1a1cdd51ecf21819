"""The modified IMK deteriorating story law (engine/stories/laws/imk.py) against OpenSees's
IMKBilin material (Nov. 2022 "AE_KI" version, openseespy 3.7.1.2) driven through the same drift
histories, and its monotonic backbone against closed forms from the parameters.

Every comparison runs the law as plain Python and compiled by numba, as the loops do.
Tolerance: 0.5% of OpenSees's peak |force| of the history, at every step (measured: below
1e-15, i.e. rounding).
"""
import math

import numpy as np
import pytest

from engine.loops.compiled import compiled_in_module
from engine.stories.laws import imk

KE = 2e8  # N/m: the story's elastic stiffness (the building's story_stiffness)
FY = 2e6  # N
UY = FY / KE  # 0.01 m
TOLERANCE = 0.005

# Every deterioration at work (the lambdas finite, c = 1), the backbone reaching its capping
# point at 4 u_y and its residual strength by 6-7 u_y, yet the energy capacity not exhausted
# by the histories below (see test_exhausted_capacity_fails_the_story for when it is).
LAW = dict(yield_force=FY, capping_ratio=1.1, plastic_deformation=3 * UY,
           post_capping_deformation=3 * UY, ultimate_deformation=15 * UY, residual_ratio=0.3,
           lambda_s=30.0, lambda_c=30.0, lambda_k=60.0, c_s=1.0, c_c=1.0, c_k=1.0,
           deterioration_factor=1.0)


def row(**changes):
    values = {**LAW, **changes}
    return imk.fields(np.array([KE]), **{k: np.array([v]) for k, v in values.items()})[0]


@pytest.fixture(scope="module")
def compiled():
    pytest.importorskip("numba")
    return compiled_in_module(imk.force)


def ours(history, force, **changes):
    """Forces (N) and failure states of a virgin story along `history` (m)."""
    par = row(**changes)
    state = imk.initial_state(par)
    forces = np.empty(history.size)
    failure = np.empty(history.size)
    for i, drift in enumerate(history):
        forces[i] = force(float(drift), state, par)
        failure[i] = state[imk.FAILURE]
    return forces, failure, state


def opensees(history, **changes):
    """IMKBilin's forces along `history`: symmetric properties, OpenSees's Lamda = lambda
    theta_p (its reference energy is Lamda F_y)."""
    ops = pytest.importorskip("openseespy.opensees")
    v = {**LAW, **changes}
    side = [v["plastic_deformation"], v["post_capping_deformation"], v["ultimate_deformation"],
            v["yield_force"], v["capping_ratio"], v["residual_ratio"]]
    lamda = [v[k] * v["plastic_deformation"] for k in ("lambda_s", "lambda_c", "lambda_k")]
    ops.wipe()
    ops.uniaxialMaterial("IMKBilin", 1, KE, *side, *side, *lamda, v["c_s"], v["c_c"],
                         v["c_k"], v["deterioration_factor"], v["deterioration_factor"])
    ops.testUniaxialMaterial(1)
    out = np.empty(history.size)
    for i, drift in enumerate(history):
        ops.setStrain(float(drift))  # a trial state, committed
        out[i] = ops.getStress()
    ops.wipe()
    return out


def cycles(multiples, per_quarter):
    """Drift history (m): two cycles at each multiple of u_y, 0 -> +a -> 0 -> -a -> 0,
    `per_quarter` equal increments per quarter cycle, starting at rest."""
    points = [np.zeros(1)]
    for a in multiples:
        up = np.linspace(0.0, a * UY, per_quarter + 1)[1:]  # 0 -> a, ending at a
        for _ in range(2):
            points += [up, a * UY - up, -up, up - a * UY]  # a -> 0, 0 -> -a, -a -> 0
    return np.concatenate(points)


GROWING = (0.5, 1, 2, 3, 4, 6, 8)


def relative_error(mine, reference):
    return np.max(np.abs(mine - reference)) / np.max(np.abs(reference))


def cycle_peaks(forces, per_quarter):
    """Peak |force| of each full cycle of a `cycles` history."""
    return np.abs(forces[1:]).reshape(-1, 4 * per_quarter).max(axis=1)


def test_cyclic_growing_amplitudes_match_opensees(compiled):
    history = cycles(GROWING, 200)
    reference = opensees(history)
    python, failure, state = ours(history, imk.force)
    jitted, _, _ = ours(history, compiled)
    # The history does what it is meant to: past the capping point into softening and the
    # residual branch (failure state 2), with cyclic deterioration of the strength (each
    # amplitude's second cycle weaker than its first past yield) and of the unloading
    # stiffness.
    assert failure.max() == 2.0
    peaks = cycle_peaks(reference, 200)
    assert FY < peaks.max() < 1.1 * FY  # hardened, the cap already lowered by then
    assert np.all(peaks[5::2] < peaks[4::2][: len(peaks[5::2])])
    assert peaks[-1] < 0.5 * FY
    assert state[imk.K_UNLOAD] < 0.6 * KE
    for mine in (python, jitted):
        assert relative_error(mine, reference) <= TOLERANCE
        assert np.max(np.abs(cycle_peaks(mine, 200) / peaks - 1)) <= TOLERANCE
    assert np.array_equal(python, jitted)


def test_monotonic_push_follows_the_closed_form_backbone(compiled):
    # Up to past the ultimate drift, then back to -8 u_y: the positive side lost, the negative
    # one keeps its residual strength only (IMKBilin's failure rule).
    f_cap = 1.1 * FY
    u_cap = UY + 3 * UY
    k_pc = f_cap / (3 * UY)
    u_res = u_cap + (f_cap - 0.3 * FY) / k_pc
    closed = {UY: FY,  # yield
              0.5 * UY: 0.5 * FY,  # elastic
              u_cap: f_cap,  # capping
              u_cap + 1 * UY: f_cap - k_pc * UY,  # post-capping
              u_res: 0.3 * FY,  # residual onset
              12 * UY: 0.3 * FY,  # residual plateau
              15 * UY: 0.0,  # ultimate: strength lost
              17 * UY: 0.0}
    push = np.unique(np.concatenate([np.linspace(0.0, 18 * UY, 1801), list(closed)]))
    history = np.concatenate([push, np.linspace(18 * UY, -8 * UY, 2601)[1:]])
    python, failure, _ = ours(history, imk.force)
    jitted, _, _ = ours(history, compiled)
    reference = opensees(history)
    par = row()
    for drift, expected in closed.items():
        i = int(np.argmin(np.abs(push - drift)))
        assert push[i] == pytest.approx(drift, abs=1e-12)
        for forces in (python, jitted, reference):
            assert forces[i] == pytest.approx(expected, rel=1e-9, abs=1e-6 * FY)
        assert imk.backbone(drift, par) == pytest.approx(expected, rel=1e-9, abs=1e-6 * FY)
        assert imk.backbone(-drift, par) == pytest.approx(-expected, rel=1e-9, abs=1e-6 * FY)
    assert np.allclose(imk.backbone(push, par), python[: push.size], rtol=1e-9, atol=1e-6 * FY)
    assert failure[push.size - 1] == 3.0  # positive strength lost
    back = python[push.size:]
    assert back.min() == pytest.approx(-0.3 * FY)  # the residual strength only
    for mine in (python, jitted):
        assert relative_error(mine, reference) <= TOLERANCE


def test_coarse_increments_give_opensees_forces_at_the_same_steps(compiled):
    # 20 points per cycle: the step crosses the backbone's corners, so the trapezoidal
    # excursion energies (and so the deterioration) differ from a fine history's, in both
    # implementations alike.
    history = cycles(GROWING, 5)
    reference = opensees(history)
    fine = opensees(cycles(GROWING, 200))
    assert not np.isclose(cycle_peaks(reference, 5)[-1], cycle_peaks(fine, 200)[-1],
                          rtol=1e-3)  # step dependent indeed
    for force in (imk.force, compiled):
        mine, _, _ = ours(history, force)
        assert relative_error(mine, reference) <= TOLERANCE
        assert np.max(np.abs(cycle_peaks(mine, 5) / cycle_peaks(reference, 5) - 1)) \
            <= TOLERANCE


def test_random_seismic_like_history(compiled):
    # A filtered random walk: white noise through a 1 Hz, 10%-damped oscillator sampled at
    # 5 ms for 40 s, scaled to a peak drift of 7 u_y.
    rng = np.random.default_rng(20240611)
    dt, omega, zeta = 0.005, 2 * math.pi, 0.10
    x = v = 0.0
    drift = np.empty(8000)
    for i, a in enumerate(rng.standard_normal(drift.size)):
        v += dt * (a - 2 * zeta * omega * v - omega ** 2 * x)
        x += dt * v
        drift[i] = x
    history = np.concatenate([[0.0], drift * (7 * UY / np.max(np.abs(drift)))])
    # Its many cycles dissipate more than the cyclic histories': a larger capacity keeps it
    # short of exhaustion (about 3/4 of E_t dissipated; with lambda 30 it is exhausted).
    larger = dict(lambda_s=80.0, lambda_c=80.0, lambda_k=160.0)
    reference = opensees(history, **larger)
    python, failure, _ = ours(history, imk.force, **larger)
    jitted, _, _ = ours(history, compiled, **larger)
    assert failure.max() == 2.0 and np.max(np.abs(reference)) > FY
    assert np.max(np.abs(reference[-2000:])) < 0.8 * FY  # deteriorated
    for mine in (python, jitted):
        assert relative_error(mine, reference) <= TOLERANCE


def test_exhausted_capacity_fails_the_story(compiled):
    # A small energy capacity (lambda 10): the excursion that ends near 5.4 u_y brings the
    # dissipated energy past E_t. Ibarra et al. (2005): the capacity is exhausted, the story
    # fails (both ways). IMKBilin computes a negative beta there, clips it to 0 and carries on
    # at its residual strength for good: the one deliberate difference.
    history = cycles(GROWING, 200)
    small = dict(lambda_s=10.0, lambda_c=10.0, lambda_k=20.0)
    reference = opensees(history, **small)
    for force in (imk.force, compiled):
        mine, failure, state = ours(history, force, **small)
        failed = int(np.argmax(failure == 5.0))
        assert failed > 0 and np.all(mine[failed:] == 0.0)
        assert state[imk.ENERGY] > 10.0 * FY * 3 * UY  # E_t = lambda F_y theta_p
        assert relative_error(mine[:failed], reference[:failed]) <= 1e-9
        assert np.max(np.abs(reference[failed:])) > 0.3 * FY  # OpenSees still standing


def test_no_deterioration_with_infinite_lambdas(compiled):
    # lambda = inf: a bilinear hysteresis under the backbone, equal cycles at one amplitude.
    history = cycles((3, 3, 3), 50)
    mine, _, state = ours(history, compiled, lambda_s=math.inf, lambda_c=math.inf,
                          lambda_k=math.inf)
    peaks = cycle_peaks(mine, 50)
    assert np.allclose(peaks, FY + (0.1 * FY / (3 * UY)) * 2 * UY, rtol=1e-9)
    assert state[imk.K_UNLOAD] == KE


def test_declaration_fields_and_check():
    assert imk.NAME == "imk" and imk.ORDER == 3
    assert imk.N_STATE <= 32
    par = row()
    assert par.shape == (imk.N_FIELDS,)
    assert par[imk.UCAP0] == pytest.approx(4 * UY)
    assert par[imk.EREF_S] == pytest.approx(30.0 * FY * 3 * UY)
    assert imk.initial_state(par).shape == (imk.N_STATE,)
    two = imk.fields(np.array([KE, 2 * KE]),
                     **{k: np.full(2, v) for k, v in LAW.items()})
    assert two.shape == (2, imk.N_FIELDS) and two[1, imk.UCAP0] == pytest.approx(3.5 * UY)
    with pytest.raises(ValueError, match="ultimate_deformation"):
        imk.check(**{**LAW, "ultimate_deformation": 2 * UY})
    imk.check(**LAW)
    assert imk.PARAMETERS.yield_force.required
    assert imk.PARAMETERS.ultimate_deformation.default == math.inf
