"""Sweeps of a building that twists: every member is the engine's run (its pair, angle, wall
and bumpers where they stand), the contact points labelled along `point` (their wall and
position), NetCDF and Zarr alike; bumper positions belong to a run's key."""
import dataclasses
import functools

import numpy as np
import pytest

import engine
import pipeline
from pipeline.errors import SweepError
from pipeline.records import RecordPair, load_pair
from tests.helpers import assert_udunits

SECONDS = 6.0
BUILDING = engine.Building(torsion=engine.Torsion(
    plan_size=(30.0, 20.0), mass_offset=(2.0, -1.0),
    isolator_positions=((-15.0, -10.0), (15.0, -10.0), (15.0, 10.0), (-15.0, 10.0))))
PADS = ((-5.0, 5.0), (-8.0, 8.0))  # m along the x walls, the y walls


@functools.cache
def short_pair() -> RecordPair:
    """RSN953's first SECONDS: the slab reaches the walls within them."""
    x, y = load_pair("RSN953")
    n = int(SECONDS / x.dt) + 1
    cut = [dataclasses.replace(r, accel=r.accel[:n]) for r in (x, y)]
    return RecordPair("RSN953-6s", *cut)


@pytest.fixture(scope="module", params=["nc", "zarr"])
def twisting(request, tmp_path_factory):
    out = tmp_path_factory.mktemp("torsion") / f"torsion.{request.param}"
    ds = pipeline.sweep([short_pair()], gap=[0.03, 0.05], impact="linear", angle=[0.0, 60.0],
                        moat="rectangular", building=BUILDING, quiet=True, out=out)
    return ds.load()


def test_every_member_is_the_engine_run(twisting):
    pair = short_pair()
    gaps, angles = np.repeat([0.03, 0.05], 2), np.tile([0.0, 60.0], 2)
    alone = engine.simulate(pair.accel, pair.dt, engine.Contact.linear(gaps), BUILDING,
                            moat="rectangular", angle=angles)
    peaks = {**alone.peaks(), **alone.plan_peaks(), **alone.torsion_peaks()}
    for name, value in peaks.items():
        got = twisting[name].isel(record=0).transpose("gap", "angle", ...)
        np.testing.assert_array_equal(got.values.reshape(value.shape), value, err_msg=name)
    assert (twisting.n_impacts.sel(gap=0.03) > 0).all() and (twisting.peak_rotation > 0).all()


def test_the_points_are_labelled(twisting):
    ds = twisting
    assert ds.max_point_force.dims[-1] == "point"
    assert list(ds.point_wall.values) == ["+x", "+x", "-x", "-x", "+y", "+y", "-y", "-y"]
    np.testing.assert_array_equal(ds.point_along.values, [-10, 10, -10, 10, -15, 15, -15, 15])
    assert ds.point_along.attrs["units"] == "m"
    assert ds.peak_rotation.attrs["units"] == "rad"
    assert_udunits(ds)


def test_bumpers_where_they_stand(tmp_path):
    pair = short_pair()
    ds = pipeline.sweep([pair], gap=0.08, thickness=0.05, n_bumpers=[2, 3], moat="rectangular",
                        building=BUILDING, bumper_positions=PADS, quiet=True)
    np.testing.assert_array_equal(ds.point_along.values, [-5, 5, -5, 5, -8, 8, -8, 8])
    alone = engine.simulate(pair.accel, pair.dt, engine.Contact.bumper(0.08, n_bumpers=[2, 3]),
                            BUILDING, moat=engine.Moat("rectangular", bumper_positions=PADS))
    np.testing.assert_array_equal(ds.max_point_force.isel(record=0).values,
                                  alone.max_point_force)
    assert (alone.max_point_force > 0).any()
    with pytest.raises(SweepError, match="bumper_positions: the plan model takes none.*"
                                          "twisting model takes it: a building with a torsion"):
        pipeline.sweep([pair], gap=0.10, moat="rectangular", bumper_positions=PADS, quiet=True)
    for moat in (None, "circular"):  # refused before any compute, quoting the model's table
        with pytest.raises(SweepError, match="give moat='rectangular'|the twisting model "
                                             "takes 'rectangular'"):
            pipeline.sweep(["RSN953"] if moat is None else [pair], gap=0.10, moat=moat,
                           building=BUILDING, quiet=True)


def test_bumper_positions_are_part_of_the_key():
    from pipeline.execute.keys import context_key

    pair = short_pair()
    keys = {context_key(pair, 5e-4, BUILDING, "rectangular", None, positions)
            for positions in (None, PADS, ((-5.0, 5.0), (-8.0, 0.0)))}
    assert len(keys) == 3
    # a run without bumper positions keeps the key it had before they existed
    assert context_key(pair, 5e-4, BUILDING, "rectangular") == \
        context_key(pair, 5e-4, BUILDING, "rectangular", None, None)


def test_the_accidental_eccentricity_is_a_sweep_dimension():
    """accidental_eccentricity (a fraction of the plan, engine.torsion.shifted) moves the mass
    of each member: the engine's run of the building so moved; a building that does not twist, or a
    planar run, refuses it before any compute."""
    pair = short_pair()
    ds = pipeline.sweep([pair], gap=0.03, impact="linear", moat="rectangular",
                        building=BUILDING, accidental_eccentricity=[0.0, 0.05], quiet=True)
    assert ds.peak_rotation.dims == ("record", "accidental_eccentricity") \
        and ds.accidental_eccentricity.attrs["units"] == "1"
    moved = dataclasses.replace(BUILDING, torsion=dataclasses.replace(
        BUILDING.torsion, mass_offset=(2.0 + 1.5, -1.0 + 1.0)))
    alone = engine.simulate(pair.accel, pair.dt, engine.Contact.linear(0.03), moved,
                            moat="rectangular")
    np.testing.assert_array_equal(ds.peak_corner_disp.sel(accidental_eccentricity=0.05).values,
                                  alone.peak_corner_disp)
    for kwargs in ({"building": engine.Building(), "moat": "rectangular"},
                   {"building": BUILDING}):
        with pytest.raises(SweepError, match="torsion|in plan"):
            pipeline.sweep([pair] if "moat" in kwargs else ["RSN953"], gap=0.03,
                           impact="linear", accidental_eccentricity=[0.05], quiet=True, **kwargs)


def test_the_bumpers_stress_is_judged_on_the_pad_that_takes_most():
    """A slab that turns loads one pad beyond its share of the wall: invalid_bumper_stress
    follows each pad's own force (here each position one of the wall's two pads), not the
    wall's total shared equally, which would let a run past the rubber's range through."""
    from pipeline.assess.validity import RUBBER_STRESS_LIMIT

    area = 0.150 * 0.150  # m^2: the declared pad
    ds = pipeline.sweep([short_pair()], gap=[0.06, 0.08], thickness=0.05, n_bumpers=2,
                        moat="rectangular", building=BUILDING, bumper_positions=PADS,
                        quiet=True)
    pad = ds.max_point_force.max("point") / area
    shared = ds.max_impact_force / (2 * area)
    np.testing.assert_array_equal(ds.invalid_bumper_stress, pad > RUBBER_STRESS_LIMIT)
    assert ((pad > RUBBER_STRESS_LIMIT) & (shared <= RUBBER_STRESS_LIMIT)).any()


def test_the_command_line_sweeps_a_building_that_twists(tmp_path, capsys):
    """`python -m studies.sweep`: the plan from --building, the accidental eccentricity a
    dimension, the bumpers where --bumpers-along-x / -y put them; one of the two alone is a
    one-line error."""
    import xarray as xr

    from studies import sweep

    common = ["--records", "RSN953", "--moat", "rectangular", "--building",
              "torsion.plan_size=30,20", "--gap-cm", "10", "--quiet"]
    assert sweep.main([*common, "--accidental-eccentricity", "0", "0.05", "--bumpers-along-x",
                       "-5", "5", "--bumpers-along-y", "0", "--out", str(tmp_path)]) == 0
    with xr.open_dataset(tmp_path / "sweep.nc") as ds:
        assert list(ds.accidental_eccentricity.values) == [0.0, 0.05]
        np.testing.assert_array_equal(ds.point_along.values, [-5, 5, -5, 5, 0, 0])
        assert float(ds.peak_rotation.sel(accidental_eccentricity=0.0).max()) < 1e-15 \
            < float(ds.peak_rotation.sel(accidental_eccentricity=0.05).min())
    assert sweep.main([*common, "--bumpers-along-x", "0", "--out", str(tmp_path / "x")]) == 2
    assert "go together" in capsys.readouterr().err
