"""studies.design: the quick run's archive, its choice, and its numbers against direct engine
runs. (The optimum's nature, the space's bounds and the search's constraints on hand-made
numbers: tests/studies/design/.)"""
from __future__ import annotations

import json

import numpy as np
import pytest

from engine.results import MODE
from pipeline.assess import validity
from pipeline.assess.outcomes import weighted_quantiles
from studies import design
from studies.common.recipe import verdicts
from studies.design import archive as design_archive
from studies.design import search, space
from tests.helpers import (
    assert_collapse_modes,
    assert_on_variables_page,
    assert_udunits,
    run_recipe,
)

"""Loose bounds for the tables below: the bumpers may protrude 10 cm, c/t up to 0.4."""


# --------------------------------------------------------------------- the quick run


@pytest.fixture(scope="module")
def archive(tmp_path_factory):
    # a gap narrower than the default, where the quick search's stress limit still binds and
    # some candidates pass (0.6 D_M: 4 of 13 since the isolation damping is counted once, 11
    # without the stress limit; at 0.5 D_M none passes)
    return run_recipe(design, ["--quick", "--gap-dm", "0.6"], tmp_path_factory.mktemp("design"))


def test_archive(archive):
    ds = archive
    assert ds.peak_floor_accel.dims == ("record", "level", "candidate")
    assert ds.reference_peak_floor_accel.dims == ("record", "level", "reference")
    assert ds.sizes["record"] == len(space.QUICK_PAIRS) and ds.sizes["level"] == 3
    assert set(np.unique(ds.stage.values)) == {0, 1}
    assert_udunits(ds)
    assert_on_variables_page(ds, "design.nc")
    # the statistics are the per-pair values', weighted per earthquake
    w = ds.record_weight.values
    for name, q in (("p16", 0.16), ("median", 0.5), ("p84", 0.84)):
        np.testing.assert_array_equal(
            ds[f"{name}_peak_floor_accel"].values,
            weighted_quantiles(ds.peak_floor_accel.values, w, [q])[0])
    within = (ds.invalid_bumper_stress == 0) & (ds.crushed == 0)
    np.testing.assert_allclose(ds.fraction_within_limits.values,
                               search.weighted_fraction(within.values, w))
    # every flag counted, per level and candidate, references too
    for name in ("invalid_bumper_stress", "invalid_bumper_strain", "invalid_floor_accel",
                 "invalid_story_shear", "invalid_wall_force"):
        np.testing.assert_array_equal(ds[f"n_{name}"].values, ds[name].sum("record").values)
        np.testing.assert_array_equal(ds[f"reference_n_{name}"].values,
                                      ds[f"reference_{name}"].sum("record").values)
    # a bumper over the stress limit is flagged: stress = force / (n A)
    stress = ds.max_impact_force / (ds.n_bumpers * ds.bumper_area)
    np.testing.assert_array_equal(ds.invalid_bumper_stress.values,
                                  (stress > ds.attrs["bumper_stress_limit"]).values)
    # and past the calibration's strain: indentation > 0.8 t (a crushed bumper, here)
    strained = ds.max_indentation > validity.RUBBER_STRAIN_LIMIT * ds.thickness
    np.testing.assert_array_equal(ds.invalid_bumper_strain.values, strained.values)
    assert not (ds.invalid_bumper_strain.astype(bool) & (ds.crushed == 0)).any()
    # the pads' stiffness: Eq. 11 x the law's shape ratio of their shape factor
    from engine.impact.laws import rubber_bumper
    assert ds.attrs["bumper_shape_k"] == rubber_bumper.GENT_LINDLEY_K
    np.testing.assert_allclose(ds.shape_ratio.values, rubber_bumper.compression_ratio(
        ds.shape_factor.values, ds.attrs["bumper_shape_k"]), rtol=1e-12)
    # no wall, the bare wall and the code's design are never hit at the service level
    assert int(ds.reference_n_impacts.isel(level=0).sum()) == 0
    assert ds.attrs["D_TM"] > ds.attrs["D_M"] > ds.attrs["design_gap"]
    assert len(verdicts(ds)) == 4
    # the long names and units the declarations give, worded as the archive always had them
    assert ds.crushed.attrs == {"units": "1",
                                "long_name": "1 where the bumpers are crushed beyond delta_u"}
    assert ds.peak_interstory_drift.attrs["long_name"] == (
        "largest peak interstory drift over the stories (resultant in plan)")
    assert "(linear law, k 2500 kN/mm, COR 0.5)" in ds.reference.attrs["long_name"]


def test_how_each_run_ended_is_stored_and_counted_by_mode(archive):
    """collapse_mode per pair beside invalid_collapse, candidates and references, counted per
    level and candidate by mode (n_invalid_collapse_by_mode) and in all (collapse_modes);
    the table's flagged pairs name the modes (here of made-up collapses: the quick run does
    not collapse)."""
    ds = archive
    for prefix in ("", "reference_"):
        mode = ds[prefix + "collapse_mode"]
        assert mode.dims == ds[prefix + "invalid_collapse"].dims
        assert_collapse_modes(mode, ds[prefix + "invalid_collapse"].values)
        by_mode = ds[prefix + "n_invalid_collapse_by_mode"]
        assert by_mode.dims == ("mode",) + ds[prefix + "n_invalid_collapse"].dims
        np.testing.assert_array_equal(by_mode.sum("mode"), ds[prefix + "n_invalid_collapse"])
        for code, name in enumerate(by_mode.mode.values, start=1):
            np.testing.assert_array_equal(by_mode.sel(mode=name),
                                          (mode == code).sum("record"))
    assert json.loads(ds.attrs["collapse_modes"])["candidates"]["collapsed"] \
        == int(ds.invalid_collapse.sum())
    made = ds.copy(deep=True)
    made.collapse_mode[:2, 2, 0] = [MODE.story_drift, MODE.numerical_instability]
    made.n_invalid_collapse[2, 0] = 2
    assert design_archive.flagged_text(made, "", "candidate", 0, 2).endswith(
        "2 collapsed (1 story drift, 0 isolator capacity, 1 numerical instability)")


def test_choice_is_the_best_feasible_and_its_nature_is_reported(archive):
    ds = archive
    chosen = int(ds.attrs["chosen_candidate"])
    assert chosen >= 0 and int(ds["rank"][chosen]) == 1
    feasible = ds.feasible.values.astype(bool)
    margins = np.array([ds[f"margin_{c}"].values for c in space.CRITERIA])
    np.testing.assert_array_equal(feasible, np.all(margins >= -1e-12, axis=0))
    assert ds.objective.values[chosen] == ds.objective.values[feasible].min()
    assert np.all(ds["rank"].values[~feasible] == 0)
    within = ds.fraction_within_limits.isel(level=2).values
    assert np.all(within[feasible] >= ds.attrs["within_limits_required"])
    assert np.all(ds.fraction_contact.isel(level=0).values[feasible] == 0)
    # the nature: every bound named with its kind; a physical one with its reason
    import json
    nature = json.loads(ds.attrs["optimum_bounds"])
    assert ds.attrs["optimum_nature"].startswith(
        "interior" if nature["interior"] else "at a bound")
    for b in nature["bounds"]:
        assert b["kind"] in ("physical", "grid") and (b["kind"] == "grid") != bool(b["why"])
    # the stress limit matters: re-judged without it (the old criterion), more candidates pass
    old = search.rejudge(ds, space.Criteria(stress_limit=False, service_contact=1.0))
    assert old["feasible"].sum() > feasible.sum()


def test_numbers_equal_direct_engine_runs(archive):
    """The chosen candidate at every level under one pair, the code's design beside it, in one
    direct engine call: the same peaks, whether the search ran the member or took the free
    run (no contact)."""
    import engine
    from pipeline.checks import resolve_pairs
    from pipeline.motions.bounds import design_basis
    from pipeline.motions.superstructure import for_basis

    ds = archive
    i = int(ds.attrs["chosen_candidate"])
    p = int(np.argmax(ds.reference_peak_isolator_disp.isel(level=2, reference=0).values))
    (pair,), _ = resolve_pairs([str(ds.record.values[p])])
    t = float(ds.thickness[i])
    bumpers = engine.Contact.bumper(
        float(ds.attrs["design_gap"]), thickness=t, cavity=float(ds.cavity[i]),
        n_bumpers=int(ds.n_bumpers[i]), k_w=float(ds.wall_k[i]),
        area=float(ds.bumper_area[i]), shape_k=float(ds.attrs["bumper_shape_k"]))
    code = engine.Contact.linear(float(ds.reference_gap[2]))
    levels = ds.level.values
    # the code-designed building (--stories imk, the default) at the archive's bound
    building = for_basis(design_basis(0.9, engine.Building(), ds.attrs["isolator_bound"])).building
    res = engine.simulate(pair.accel, pair.dt, engine.Contact.concat([bumpers] * 3 + [code] * 3),
                          building, moat="rectangular",
                          scale=float(ds.scale_factor[p]) * np.tile(levels, 2))
    assert ds.n_impacts.values[p, :, i].tolist()[0] == 0  # not run at the service level
    assert ds.n_impacts.values[p, 2, i] > 0
    for name, got in (("peak_floor_accel", res.peak_total_accel.max(axis=1)),
                      ("peak_isolator_disp", res.peak_isolator_disp),
                      ("peak_interstory_drift", res.peak_interstory_drift.max(axis=1)),
                      ("max_impact_force", res.max_impact_force)):
        np.testing.assert_array_equal(got[:3], ds[name].values[p, :, i], err_msg=name)
        np.testing.assert_array_equal(got[3:], ds[f"reference_{name}"].values[p, :, 2],
                                      err_msg=name)
    crushed = res.max_indentation[:3] > bumpers.delta_u[0]
    np.testing.assert_array_equal(crushed, ds.crushed.values[p, :, i].astype(bool))


@pytest.mark.parametrize("argv, match", [
    (["--within-limits", "1.5"], "--within-limits"),
    (["--gap-dm", "0.1"], "leaves no room for bumpers"),
    (["--building", "k9=1"], "--building"),
    (["--building", "k2=abc"], "not a number"),
])
def test_bad_options(argv, match, tmp_path, capsys):
    assert design.main([*argv, "--quick", "--records", "RSN848", "--out", str(tmp_path)]) == 2
    assert match in capsys.readouterr().err
