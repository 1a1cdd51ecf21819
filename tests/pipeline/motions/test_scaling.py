"""Records at a common intensity: scale factors, the engine's per-member scale, the search for
the factor that brings a record to a design displacement."""
from __future__ import annotations

import numpy as np
import pytest

import engine
import pipeline
from pipeline.errors import SweepError
from pipeline.motions.scaling import scale_to_displacement
from pipeline.records import RecordError, load_record, resolve_records


@pytest.fixture(scope="module")
def pacoima():
    return load_record("pacoima")


# On the compiled loop: the NumPy loop gives its numbers on scaled members, from standing to
# collapse (tests/engine/test_building_collapse.py::test_collapse_ends_the_run_at_the_same_...).
@pytest.mark.parametrize("backend", ["numba"])
def test_engine_scale_equals_a_scaled_record(pacoima, backend):
    """Member-wise factors equal running the record multiplied beforehand (to round-off: the
    interpolation onto dt and the product commute up to one rounding), and a factor of 1
    changes nothing, bit for bit."""
    rec = pacoima
    n = int(8.0 / rec.dt)  # the strong-motion start: enough to yield the isolators
    accel = rec.accel[:n]
    walls = engine.Contact.concat([engine.Contact.none(1), engine.Contact.bumper(0.20)] * 2)
    factors = np.array([1.0, 1.0, 1.7, 0.6])
    both = engine.simulate(accel, rec.dt, walls, scale=factors, backend=backend)
    plain = engine.simulate(accel, rec.dt, walls, backend=backend)
    for name, value in both.peaks().items():
        np.testing.assert_array_equal(value[:2], plain.peaks()[name][:2])
    for i in (2, 3):
        alone = engine.simulate(accel * factors[i], rec.dt, walls[[i]], backend=backend)
        for name, value in alone.peaks().items():
            np.testing.assert_allclose(both.peaks()[name][i], value[0], rtol=1e-9, atol=1e-12)
    assert both.peak_isolator_disp[2] > 1.5 * both.peak_isolator_disp[0]  # it really scaled


def test_engine_scale_refuses_bad_factors(pacoima):
    walls = engine.Contact.none(2)
    for bad in ([1.0, -1.0], [1.0, np.inf], [1.0, 2.0, 3.0], "x"):
        with pytest.raises(engine.EngineError, match="scale"):
            engine.simulate(pacoima.accel[:100], pacoima.dt, walls, scale=bad)


def test_scaled_record_names_values_and_archive_coordinates(pacoima):
    recs, names = resolve_records(["pacoima*1.5", "pacoima", "RSN77:164 * 0.8"])
    # labelled as given (issue 40), the factor as the record writes it
    assert names == ["pacoima*1.5", "pacoima", "RSN77:164*0.8"]
    np.testing.assert_array_equal(recs[0].accel, pacoima.accel * 1.5)
    assert recs[0].scale == 1.5 and recs[0].unscaled_pga == pacoima.pga
    assert recs[2].pga == pytest.approx(0.8 * pacoima.pga, rel=1e-15)
    ds = pipeline.unconstrained_peaks(["pacoima*1.5", "pacoima"], dt=1e-3)
    assert ds.record_scale.values.tolist() == [1.5, 1.0]
    assert ds.record_scale.attrs["units"] == "1"
    np.testing.assert_allclose(ds.record_unscaled_pga.values, pacoima.pga, rtol=1e-15)
    np.testing.assert_allclose(ds.record_pga.values, [1.5 * pacoima.pga, pacoima.pga],
                               rtol=1e-15)
    assert ds.record_unscaled_pga.attrs["units"] == "m s-2"


@pytest.mark.parametrize("spec", ["pacoima*x", "pacoima*-1", "pacoima*0", "pacoima*inf",
                                  "pacoima*"])
def test_bad_scale_factors_are_refused(spec):
    with pytest.raises(RecordError, match="scale factor|unknown record"):
        load_record(spec)


def test_records_reach_the_design_displacement():
    """Each kept record, scaled by its rounded factor, reaches D within 0.1% when run through
    the sweeps' own path; the factors are not trivial (the records differ by 2x)."""
    suite = scale_to_displacement(["kobe", "pacoima", "olive_view", "sylmar_converter"])
    assert suite.names == [f"{k}*{float(f)!r}" for k, f in
                           zip(["kobe", "pacoima", "olive_view", "sylmar_converter"],
                               suite.factors, strict=True)]
    ds = pipeline.unconstrained_peaks(suite.records)
    reached = ds.peak_isolator_disp.values
    np.testing.assert_array_equal(reached, suite.reached)
    assert np.all(np.abs(reached / 0.30 - 1) < 1e-3)
    assert suite.factors.max() / suite.factors.min() > 1.5
    # 6 significant digits, as the archive names carry them
    assert all(float(f"{f:.6g}") == f for f in suite.factors)


def test_records_out_of_range_are_reported_not_kept():
    """A weak record needs far more than 5x to drive the isolator 30 cm: excluded, with the
    factor it would need; a limit below every factor excludes all."""
    suite = scale_to_displacement(["pacoima", "RSN1690:360"])
    assert suite.names[0].startswith("pacoima*") and len(suite.records) == 1
    ((name, needed, reason),) = suite.excluded
    assert name == "RSN1690:360"  # as given (issue 40)
    assert needed > 5 and "highest factor" in reason
    low = scale_to_displacement(["pacoima"], limits=(2.0, 5.0))
    assert not low.records and "lowest factor" in low.excluded[0][2]
    assert low.excluded[0][1] < 2.0


def test_displacement_rule_brings_a_pair_in_plan_to_d_m():
    """pipeline.motions.rules.displacement, the pairs' search (not this module's): the factor
    is the upper end of its last bracket, so the pair reaches D_M in plan there and not
    2e-4 lower; every pair is kept, with no spectra to show."""
    from types import SimpleNamespace

    from pipeline.motions.rules import displacement
    from pipeline.records import load_pair

    x, y = load_pair("RSN953")
    n = int(round(15.0 / x.dt))
    pair = SimpleNamespace(accel=np.column_stack([x.accel, y.accel])[:n], dt=x.dt, name="x")
    building = engine.Building()
    chosen, factors, scaled = displacement.factors([pair], None, SimpleNamespace(d_m=0.25),
                                                   building, None)
    assert chosen == [0] and scaled is None and factors.shape == (1,)
    peaks = engine.simulate(pair.accel, pair.dt, engine.Contact.none(2), building,
                            engine.DEFAULT_DT, scale=factors[0] * np.array([1 - 2e-4, 1.0]),
                            moat="circular").peak_isolator_disp
    assert peaks[0] < 0.25 <= peaks[1] < 0.25 * (1 + 1e-3)


@pytest.mark.parametrize("kwargs", [{"displacement": -0.3}, {"displacement": float("nan")},
                                    {"limits": (5.0, 0.2)}, {"limits": (0.0, 1.0)},
                                    {"limits": 3}])
def test_bad_search_arguments(kwargs):
    with pytest.raises(SweepError):
        scale_to_displacement(["pacoima"], **kwargs)
