"""studies.design: the optimum's nature on hand-made candidate tables, the constraints on known
numbers, and the quick run's archive, its choice, and its numbers against direct engine runs."""
from __future__ import annotations

import numpy as np
import pytest

from pipeline.assess import validity
from pipeline.assess.outcomes import weighted_quantiles
from studies import design
from studies.common.recipe import verdicts
from studies.design import optimum, search, space
from tests.helpers import assert_udunits, run_recipe

# --------------------------------------------------------------------- hand-made tables

BOUNDS = space.Bounds(gap=0.20, clearance=0.10, usable_strain=0.6, wall_length=100.0)
"""Loose bounds for the tables below: the bumpers may protrude 10 cm, c/t up to 0.4."""
AXES = {"thickness": (0.04, 0.06, 0.08), "cavity_ratio": (0.0, 0.1, 0.2),
        "n_bumpers": (4, 8, 16), "shape_factor": (0.6, 0.8, 1.0), "wall_k": (5e8, 1e9, 2e9)}


def table_of(axes=AXES) -> dict:
    mesh = np.meshgrid(*(np.asarray(axes[v], float) for v in space.VARIABLES), indexing="ij")
    return {v: m.ravel() for v, m in zip(space.VARIABLES, mesh, strict=True)}


def at(table, **config) -> int:
    same = np.ones(table["thickness"].size, dtype=bool)
    for name, value in config.items():
        same &= np.isclose(table[name], value)
    return int(np.flatnonzero(same)[0])


def centre(axes=AXES) -> dict:
    return {v: axes[v][1] for v in space.VARIABLES}


def test_an_optimum_inside_the_grid_is_interior():
    table = table_of()
    found = optimum.nature(table, at(table, **centre()), BOUNDS)
    assert found.interior and not found.bounds
    assert found.text().startswith("interior")


def test_an_optimum_at_the_grids_edge_is_named_and_may_lie_beyond():
    table = table_of()
    found = optimum.nature(table, at(table, **{**centre(), "thickness": 0.08}), BOUNDS)
    assert not found.interior
    (bound,) = found.bounds
    assert (bound["variable"], bound["side"], bound["kind"]) == ("thickness", "upper", "grid")
    assert "thickness at its upper bound 0.08 m" in found.text()
    assert "the optimum may lie beyond the grid" in found.text()


def test_an_optimum_on_a_physical_bound_names_it():
    # 8 cm bumpers without cavity protrude 8 cm: the most a 14 cm gap leaves beyond 6 cm
    tight = space.Bounds(gap=0.14, clearance=0.06, usable_strain=0.6, wall_length=100.0)
    table = table_of()
    best = at(table, **{**centre(), "thickness": 0.08, "cavity_ratio": 0.0})
    found = optimum.nature(table, best, tight)
    kinds = {(b["variable"], b["side"]): b["kind"] for b in found.bounds}
    assert kinds == {("thickness", "upper"): "physical", ("cavity_ratio", "lower"): "physical"}
    assert "(physical: the clearance: thickness - cavity <= gap - D_S" in found.text()


def test_a_tie_at_a_bound_is_indifferent_and_a_failing_neighbour_an_active_constraint():
    table = table_of()
    best = at(table, **{**centre(), "wall_k": 2e9})
    scores = np.column_stack([np.arange(table["thickness"].size, dtype=float)] * 2)
    scores[at(table, **{**centre(), "wall_k": 1e9})] = scores[best]  # k_w plays no part
    fails = [[] for _ in scores]
    fails[at(table, **{**centre(), "wall_k": 2e9, "thickness": 0.04})] = ["within_limits"]
    found = optimum.nature(table, best, BOUNDS, fails=fails, scores=scores)
    assert found.interior and found.bounds[0]["indifferent"]
    assert found.active == ({"variable": "thickness", "side": "lower", "neighbour": 0.04,
                             "fails": ["within_limits"]},)
    assert "indifferent: wall_k" in found.text() and "thickness 0.04 m fails within_limits" \
        in found.text()
    # without the tie, the wall's bound holds the optimum
    distinct = np.column_stack([np.arange(table["thickness"].size, dtype=float)] * 2)
    assert not optimum.nature(table, best, BOUNDS, scores=distinct).interior


def test_bounds_from_physical_limits():
    b = space.Bounds(gap=0.131, clearance=0.048, usable_strain=0.589, wall_length=18.0)
    limits = b.limits({"thickness": 0.10, "cavity_ratio": 0.2, "n_bumpers": 8,
                       "shape_factor": 0.5, "wall_k": 1.5e9})
    assert limits["thickness"][1][0] == pytest.approx(0.083 / 0.8)  # t (1 - c/t) <= room
    assert limits["cavity_ratio"][1][0] == pytest.approx(0.411)
    assert limits["n_bumpers"][1][0] == pytest.approx(18.0 / (2 * 4 * 0.5 * 0.10))
    # the neighbours stop at a bound, exactly on it
    config = {"thickness": 0.10, "cavity_ratio": 0.4, "n_bumpers": 8, "shape_factor": 0.5,
              "wall_k": 2.5e9}
    near = space.neighbours(config, 0, b)
    up = near["cavity_ratio"] > 0.4
    assert near["cavity_ratio"][up].tolist() == [pytest.approx(0.411)]
    assert not np.any(near["wall_k"] > 2.5e9) and not np.any(near["shape_factor"] < 0.5)
    assert all(b.allows(space.row(near, i)) for i in range(near["thickness"].size))
    assert space.usable_strain(0.8, None) == 0.8
    assert space.usable_strain(0.8, 30.9e6) == pytest.approx(0.589, abs=1e-3)


# ---------------------------------------------------------------- constraints, ranking


def stats_of(**columns) -> dict:
    """Statistics (L = 3 levels, K candidates) from (K,) columns per level name."""
    k = len(next(iter(columns.values()))[0])
    out = {name: np.zeros((3, k)) for name in search.STAT_TEXT}
    for name, rows in columns.items():
        out[name] = np.asarray(rows, float)
    return out


def test_constraints_filter_known_numbers():
    zero = [0.0] * 4
    stats = stats_of(
        median_peak_floor_accel=[zero, zero, [5.0, 4.0, 3.0, 2.0]],
        p84_peak_floor_accel=[zero, zero, [6.0, 5.0, 4.0, 3.0]],
        fraction_within_limits=[zero, zero, [0.9, 0.9, 0.8, 0.5]],
        fraction_uncrushed=[zero, zero, [1.0, 1.0, 0.9, 0.6]],
        fraction_contact=[[0.0, 0.1, 0.0, 0.0], zero, zero],
        fraction_hurt=[zero, [0.0, 0.0, 0.3, 0.0], zero],
        fraction_valid=[zero, zero, [1.0] * 4])
    new = search.judge(stats, space.Criteria(), [4] * 4, [1.5e9] * 4)
    # 1: contact at the service level; 2 and 3: within limits under < 84%
    assert new["feasible"].tolist() == [True, False, False, False]
    assert new["rank"].tolist() == [1, 0, 0, 0]
    assert new["margins"]["within_limits"] == pytest.approx([0.06, 0.06, -0.04, -0.34])
    # the old criteria (uncrushed only, the service level free) admit 2 as well: it wins
    old = search.judge(stats, space.Criteria("median", stress_limit=False, service_contact=1.0),
                       [4] * 4, [1.5e9] * 4)
    assert old["rank"].tolist() == [3, 2, 1, 0]
    # hurt at the design level under at most 20%: 2 is out again; p84 as the objective
    capped = search.judge(stats, space.Criteria(stress_limit=False, service_contact=1.0,
                                                 hurt_design=0.2, objective="p84"),
                          [4] * 4, [1.5e9] * 4)
    assert capped["rank"].tolist() == [2, 1, 0, 0]
    assert capped["objective"].tolist() == [6.0, 5.0, 4.0, 3.0]


def test_ties_go_to_fewer_bumpers_then_the_stiffer_wall():
    rank = search.ranking([1.0, 1.0, 1.0, 0.5], [2.0] * 4, [8, 4, 4, 4],
                          [2.5e9, 5e8, 2.5e9, 1e9], [True, True, True, False])
    assert rank.tolist() == [3, 2, 1, 0]


def test_weighted_statistics():
    values = np.array([[1.0], [2.0], [3.0], [4.0]])
    # equal weights: Hazen's plotting positions (i - 1/2) / n, interpolated
    assert weighted_quantiles(values, np.ones(4), [0.5])[0, 0] == 2.5
    assert weighted_quantiles(values, np.ones(4), [0.125, 0.875])[:, 0].tolist() == \
        [1.0, 4.0]
    # weights 1, 3, 1, 1: the steps' midpoints 0.5/6, 2.5/6, 4.5/6, 5.5/6, interpolated
    assert weighted_quantiles(values, [1, 3, 1, 1], [2.5 / 6, 0.5])[:, 0] == \
        pytest.approx([2.0, 2.25])
    assert search.weighted_fraction([[True], [False], [True], [False]],
                                    [1, 3, 1, 1])[0] == pytest.approx(2 / 6)


# --------------------------------------------------------------------- the quick run


@pytest.fixture(scope="module")
def archive(tmp_path_factory):
    # a gap narrower than the default, where the quick search's stress limit still binds
    return run_recipe(design, ["--quick", "--gap-dm", "0.5"], tmp_path_factory.mktemp("design"))


def test_archive(archive):
    ds = archive
    assert ds.peak_floor_accel.dims == ("record", "level", "candidate")
    assert ds.reference_peak_floor_accel.dims == ("record", "level", "reference")
    assert ds.sizes["record"] == len(space.QUICK_PAIRS) and ds.sizes["level"] == 3
    assert set(np.unique(ds.stage.values)) == {0, 1}
    assert_udunits(ds)
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
