"""The plan kernel's pair arithmetic (engine/loops/numba_support.py): each lane is the scalar
operation, bit for bit, including numba's max on a NaN; rows load and store whole; and the
identity the kernel's squared peaks rest on, sqrt(x * x) == |x|."""
import numpy as np
import pytest
from numba import njit

from engine.loops.numba_support import (
    add2,
    data_pointer,
    div2,
    load_pair,
    max2,
    mul2,
    store_pair,
    sub2,
)


@njit(error_model="numpy")  # as the kernels: x / 0 is inf, not an exception
def _lanes(p0, p1, q0, q1):
    p, q = (p0, p1), (q0, q1)
    return np.array([*add2(p, q), *sub2(p, q), *mul2(p, q), *div2(p, q), *max2(p, q)])


@njit(error_model="numpy")
def _scalars(p0, p1, q0, q1):
    return np.array([p0 + q0, p1 + q1, p0 - q0, p1 - q1, p0 * q0, p1 * q1, p0 / q0, p1 / q1,
                     max(p0, q0), max(p1, q1)])


def test_each_lane_is_the_scalar_operation_bit_for_bit():
    rng = np.random.default_rng(7)
    values = rng.standard_normal((2000, 4)) * 10.0 ** rng.integers(-12, 12, (2000, 4))
    specials = [[0.0, -0.0, 1.0, -1.0], [np.nan, 1.0, 2.0, np.nan], [np.inf, -np.inf, 1.0, 3.0],
                [1.0, 2.0, 0.0, -0.0], [-0.0, 0.0, 0.0, -0.0]]
    for row in [*values, *specials]:
        lanes, scalars = _lanes(*row), _scalars(*row)
        assert lanes.tobytes() == scalars.tobytes(), row


def test_max2_passes_a_nan_value_over_as_numba_max_does():
    @njit
    def run(acc, value):
        return max2((acc, acc), (value, value))[0], max(acc, value)

    assert run(1.0, np.nan) == (1.0, 1.0)
    lane, scalar = run(np.nan, 1.0)
    assert np.isnan(lane) and np.isnan(scalar)


def test_rows_load_and_store_whole_through_a_compile_time_view():
    from numba import carray

    @njit
    def run(a):
        view = carray(data_pointer(a[1]), (3, 2))
        out = np.empty((3, 2))
        for i in range(3):
            store_pair(out, i, mul2(load_pair(view, i), (2.0, 3.0)))
        return out

    a = np.arange(12.0).reshape(2, 3, 2)
    np.testing.assert_array_equal(run(a), a[1] * [2.0, 3.0])


def test_rows_need_no_more_than_a_float64s_alignment():
    @njit
    def run(a):
        for i in range(a.shape[0]):
            store_pair(a, i, add2(load_pair(a, i), (1.0, 2.0)))

    buffer = np.zeros(7)
    start = 1 if buffer.ctypes.data % 16 == 0 else 0
    shifted = buffer[start:start + 6].reshape(3, 2)
    assert shifted.ctypes.data % 16 == 8 and shifted.flags.c_contiguous  # not 16-aligned
    run(shifted)
    np.testing.assert_array_equal(shifted, [[1.0, 2.0]] * 3)


def test_pairs_refuse_what_they_do_not_hold():
    @njit
    def wrong(a):
        return load_pair(a, 0)

    with pytest.raises(Exception, match="load_pair"):
        wrong(np.zeros((3, 2), dtype=np.float32))


def test_the_root_of_a_square_is_the_magnitude_bit_for_bit():
    # The plan kernel keeps per-direction peaks squared and roots them at the end.
    rng = np.random.default_rng(3)
    x = rng.uniform(1.0, 2.0, 10**6) * 2.0 ** rng.integers(-500, 500, 10**6)
    x[::2] *= -1.0
    np.testing.assert_array_equal(np.sqrt(x * x), np.abs(x))


def test_members_run_on_threads_kept_for_the_next_batch(monkeypatch):
    """run_members hands members to a pool it keeps (numba_support._POOLS): a second batch
    reuses its threads, and every member's steps run once per chunk whatever the pool."""
    import numba

    from engine.loops import numba_support

    monkeypatch.setattr(numba_support, "_POOLS", {})
    monkeypatch.setattr(numba, "get_num_threads", lambda: 2)
    seen = []

    def steps(members, s0, s1):
        seen.append((tuple(members.tolist()), s0, s1))

    numba_support.run_members(5, 10, None, steps)
    (pool,) = numba_support._POOLS.values()
    numba_support.run_members(3, 10, None, steps)
    assert list(numba_support._POOLS.values()) == [pool]
    assert sorted(m for members, _, _ in seen for m in members) == [0, 0, 1, 1, 2, 2, 3, 4]
    assert {(s0, s1) for _, s0, s1 in seen} == {(0, 10)}
