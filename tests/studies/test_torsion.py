"""studies.torsion --quick: the archive, the code's D_TM per eccentricity (ASCE 7-22
17.5.3.3's formula), its numbers against a direct engine run, and the verdicts' counting."""
import json

import numpy as np
import pytest

import engine
from pipeline.motions.torsion import total_maximum_displacement
from studies import torsion
from studies.torsion.verdicts import pad_share
from tests.helpers import assert_on_variables_page, assert_udunits, run_recipe


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    return run_recipe(torsion, ["--quick"], tmp_path_factory.mktemp("torsion"))


def test_archive(quick):
    ds = quick
    assert ds.peak_corner_disp.dims == ("record", "mass_offset_ratio", "angle", "gap", "barrier")
    assert ds.free_peak_corner_disp.dims == ("record", "mass_offset_ratio", "angle")
    assert ds.max_point_force.dims[-1] == "point" and ds.sizes["point"] == 8  # 2 pads a wall
    assert list(ds.gap.values) == ["0.6 D_M", "D_TM"]
    assert list(ds.mass_offset_ratio.values) == [0.0, 0.1] and ds.sizes["angle"] == 3
    assert json.loads(ds.attrs["pad_positions_m"]) == [[-5.0, 5.0], [-7.5, 7.5]]
    assert_udunits(ds)
    assert_on_variables_page(ds, "torsion.nc")
    assert len(json.loads(ds.attrs["paper_verdicts"])) == 4


def test_the_gaps_are_the_codes(quick):
    ds = quick
    d_m = float(ds.attrs["D_M"])
    for i, e in enumerate(ds.mass_offset_ratio.values):
        code = total_maximum_displacement(d_m, torsion.PLAN, (e * 30.0, e * 20.0))
        assert float(ds.D_TM[i]) == code["d_tm"]
        np.testing.assert_array_equal(ds.gap_length[i], [0.6 * d_m, code["d_tm"]])
    assert float(ds.D_TM[0]) == pytest.approx(1.15 * d_m, rel=1e-12)  # the floor governs
    assert float(ds.D_TM[1]) > 1.15 * d_m


def test_a_centred_mass_does_not_twist_an_eccentric_one_does(quick):
    ds = quick.sel(mass_offset_ratio=0.0)
    np.testing.assert_allclose(ds.free_peak_corner_disp, ds.free_peak_isolator_disp,
                               rtol=1e-9)
    assert float(ds.free_peak_rotation.max()) < 1e-15
    # a wall's two pads (or corners) take equal forces
    pads = ds.max_point_force.values.reshape(*ds.max_point_force.shape[:-1], 4, 2)
    assert (pads > 0).any()
    np.testing.assert_allclose(pads[..., 0], pads[..., 1], rtol=1e-9)
    share = pad_share(quick.sel(mass_offset_ratio=[0.0]), "bare wall")
    hit = np.isfinite(share)
    assert hit.any()
    np.testing.assert_allclose(share[hit], 0.5, rtol=1e-9)
    twisted = quick.sel(mass_offset_ratio=0.1)
    assert (twisted.free_peak_corner_disp > twisted.free_peak_isolator_disp * 1.05).all()


def test_a_run_is_the_engines(quick):
    """The first pair at 45 degrees, eccentric, bumpers at 0.6 D_M: the engine's peaks."""
    from pipeline.checks import resolve_pairs
    from pipeline.motions.code_suite import code_suite

    ds = quick
    pairs, names = resolve_pairs([str(r) for r in ds.record.values], None)
    suite = code_suite(pairs, names, engine.Building(), bound="lower")
    assert float(ds.scale_factor[0]) == suite.factors[0]
    building = engine.Building(**{**_fields(suite.building), "torsion": engine.Torsion(
        plan_size=torsion.PLAN, mass_offset=(3.0, 2.0))})
    gap = float(ds.gap_length.sel(mass_offset_ratio=0.1, gap="0.6 D_M"))
    run = engine.simulate(pairs[0].accel, pairs[0].dt,
                          engine.Contact.bumper(gap, thickness=torsion.THICKNESS, n_bumpers=2),
                          building, angle=45.0, scale=[suite.factors[0]],
                          moat=engine.Moat(bumper_positions=torsion.pad_positions(torsion.PLAN,
                                                                                  2)))
    got = ds.isel(record=0).sel(mass_offset_ratio=0.1, angle=45.0, gap="0.6 D_M", barrier="bumpers")
    for name in ("peak_corner_disp", "peak_rotation", "max_point_force", "peak_isolator_disp"):
        np.testing.assert_array_equal(got[name].values, getattr(run, name)[0], err_msg=name)


def _fields(building):
    import dataclasses

    return {f.name: getattr(building, f.name) for f in dataclasses.fields(building)}


def test_a_crushed_pads_stress_is_not_its_rubbers_and_flagged_runs_stay(quick):
    """A crushed pad's largest force is the slab bearing on the wall: no rubber stress
    (pad_stress NaN there), the flag read from the uncrushed pads alone; a flagged run keeps its
    pad share (counted beside, never dropped: issue 38)."""
    from pipeline.assess.validity import RUBBER_STRESS_LIMIT
    from studies.common.paper import AREA
    from studies.torsion.verdicts import check

    ds = quick
    crushed = ds.pad_crushed.values.astype(bool)
    stress = ds.pad_stress.values
    assert crushed.any() and (~crushed).any()
    assert np.isnan(stress[crushed]).all() and np.isfinite(stress[~crushed]).all()
    force = ds.max_point_force.sel(barrier="bumpers").values
    np.testing.assert_array_equal(stress[~crushed], force[~crushed] / AREA)
    np.testing.assert_array_equal(ds.invalid_pad_stress.values,
                                  (np.nan_to_num(stress) > RUBBER_STRESS_LIMIT).any(axis=-1))
    share = pad_share(ds, "bumpers")
    walls = ds.max_impact_force_wall.sel(barrier="bumpers").values
    np.testing.assert_array_equal(np.isfinite(share), walls.max(axis=-1) > 0)
    verdict = next(v for v in check(ds) if "(bumpers)" in v.claim)
    assert verdict.numbers["invalid_runs_with_contact"] == int(
        (ds.invalid_pad_stress.values.astype(bool) & np.isfinite(share)).sum())
