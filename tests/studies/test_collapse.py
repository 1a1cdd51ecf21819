"""studies.collapse: FEMA P695 chapter 7 for the code-designed isolated building and its moat: the
quick archive's S_CT and P(collapse | MCE_R) recomputed from its per-pair collapse intensities,
and how each run collapsed (collapse_mode) counted by mode.
And studies.loss on the quick collapse run's fragilities: its archive holds the repair cost and
time per stripe and configuration with their quantiles, the expected annual loss and the annual
rates per configuration, pelicun's version; its expected annual loss and annual rates recompute
from its own conditional values and hazard curve (FEMA P-58-1 chapter 8), and its collapse rate
from the collapse fragility. (studies.loss is tested here, on the quick collapse run made once;
the assessment's functions on hand-made data: tests/pipeline/assess/test_collapse.py.)"""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.stats import norm

from engine.results import COLLAPSE_MODES
from engine.units import CM
from pipeline.assess import collapse as pc
from studies import collapse
from tests.helpers import (
    assert_collapse_modes,
    assert_on_variables_page,
    assert_udunits,
    run_recipe,
)


@pytest.fixture(scope="module")
def quick_path(tmp_path_factory):
    """The quick collapse run's folder (its archive: quick/collapse.nc), which the loss
    study's quick run below reads too (the collapse study then runs once)."""
    out = tmp_path_factory.mktemp("collapse")
    run_recipe(collapse, ["--quick"], out)
    return out


@pytest.fixture(scope="module")
def quick(quick_path):
    import xarray as xr

    with xr.open_dataset(quick_path / "quick" / "collapse.nc") as ds:
        return ds.load()


def test_the_archive_recomputes_from_its_pairs(quick):
    ds = quick
    assert_udunits(ds)
    assert_on_variables_page(ds, "collapse.nc")
    assert ds.attrs["scaling_rule"] == "p695" and ds.attrs["isolator_bound"] == "lower"
    assert "imk" in ds.attrs["story_law"] and ds.attrs["p_delta"] == 1
    weights = ds.record_weight.values
    for barrier in ds.barrier.values:
        for g in range(ds.gap_fraction.size):
            cell = ds.sel(barrier=barrier).isel(gap_fraction=g)
            intensity = cell.collapse_intensity.values
            censored = cell.collapse_censored.values.astype(bool)
            # the first level at which the pair collapses, from the stored runs
            fell = cell.collapsed.values.astype(bool)  # (record, level)
            first = [ds.level.values[np.argmax(f)] if f.any() else np.nan for f in fell]
            np.testing.assert_array_equal(intensity, first)
            s_ct, known, _ = pc.collapse_median(intensity, censored, weights,
                                                ds.level.values[-1])
            acmr = cell.ssf.item() * (s_ct.item() if known else ds.level.values[-1])
            empirical, _ = pc.median_collapse(intensity, censored, weights)
            np.testing.assert_equal(cell.s_ct_empirical.item(), empirical)
            assert cell.acmr.item() == acmr
            p = norm.cdf(-math.log(acmr) / cell.beta_total.item())
            assert cell.collapse_probability.item() == pytest.approx(p, rel=1e-12)
    # the paired bootstrap: the interval holds the estimate, the bare wall's ratio is 1
    interval = ds.collapse_probability_interval
    point = ds.collapse_probability
    assert (interval.isel(interval_bound=0) <= point + 1e-12).all()
    assert (interval.isel(interval_bound=1) >= point - 1e-12).all()
    assert (ds.collapse_probability_ratio.sel(barrier="bare wall") == 1).all()
    np.testing.assert_array_equal(
        ds.collapse_probability_ratio_interval.sel(barrier="bare wall").values, 1.0)
    assert ds.sizes["draw"] == 1000
    table = ds.attrs["paper_verdicts"]
    assert "Kitayama & Constantinou" in table and "Masroor & Mosqueda" in table


def test_the_archive_says_how_each_run_collapsed(quick):
    """collapse_mode beside collapsed (the building collapses by its stories' drift), and at
    each pair's collapse intensity; the attribute collapse_modes counts each mode."""
    ds = quick
    assert ds.collapse_mode.dims == ds.collapsed.dims
    assert_collapse_modes(ds.collapse_mode, ds.collapsed.values)
    assert ds.collapsed.values.any() and not ds.collapsed.values.all()
    assert_collapse_modes(ds.collapse_intensity_mode, ~ds.collapse_censored.values.astype(bool))
    # unrefined (quick): the mode of the pair's first collapsing level
    codes = ds.collapse_mode.transpose("record", "level", ...).values
    first = np.argmax(codes != 0, axis=1)[:, None]
    np.testing.assert_array_equal(ds.collapse_intensity_mode.values,
                                  np.take_along_axis(codes, first, axis=1)[:, 0])
    collapses, modes = (json.loads(ds.attrs[k]) for k in ("collapses", "collapse_modes"))
    for barrier, numbers in modes.items():
        codes = ds.collapse_mode.sel(barrier=barrier).values
        assert numbers == {"collapsed": collapses[barrier],
                           **{m: int((codes == code).sum())
                              for code, m in enumerate(COLLAPSE_MODES) if code}}


def test_refinement_bisects_between_the_last_standing_and_the_first_collapse(quick,
                                                                             tmp_path):
    ds = run_recipe(collapse, ["--quick", "--refinements", "2"], tmp_path)
    assert ds.attrs["refinements"] == 2
    coarse, fine = quick.collapse_intensity.values, ds.collapse_intensity.values
    np.testing.assert_array_equal(np.isnan(coarse), np.isnan(fine))
    levels = list(ds.level.values)
    known = ~np.isnan(coarse)
    below = np.array([levels[levels.index(c) - 1] if levels.index(c) else 0.5 * levels[0]
                      for c in coarse[known]])
    assert np.all((fine[known] <= coarse[known]) & (fine[known] > below))
    # two bisections: a quarter of the step, on the grid of quarters
    quarters = (fine[known] - below) / ((coarse[known] - below) / 4)
    np.testing.assert_allclose(quarters, np.round(quarters), atol=1e-9)
    assert np.any(fine[known] < coarse[known])
    assert_collapse_modes(ds.collapse_intensity_mode, known)


def test_each_pair_runs_in_both_orientations_sharing_its_weight(quick):
    """FEMA P695's two runs of a pair in a three-dimensional model: each pair as recorded and
    with its components swapped (its name + " swapped", the same MCE_R factor), its two
    records sharing the pair's weight and earthquake. This building (isotropic isolators, the
    same story law along x and y) in its square moat is symmetric under the exchange of x and
    y: the swapped pair's run is the pair's, reflected, every resultant peak the same to
    round-off (the triple friction pendulums' solve in plan takes x before y; on the paper's
    bilinear isolators bit for bit: tests/pipeline/motions/test_code_suite.py) and every run
    ending alike (a building that differs along y would tell its orientations apart)."""
    from pipeline.motions.code_suite import ORIENTATIONS, SWAPPED

    ds = quick
    names = [str(n) for n in ds.record.values]
    half = len(names) // 2
    assert len(names) == 2 * collapse.QUICK_PAIRS
    assert names[half:] == [n + SWAPPED for n in names[:half]]
    assert list(ds.record_orientation.values) == [ORIENTATIONS[0]] * half \
        + [ORIENTATIONS[1]] * half
    np.testing.assert_array_equal(ds.scale_factor.values[:half], ds.scale_factor.values[half:])
    np.testing.assert_array_equal(ds.record_event.values[:half], ds.record_event.values[half:])
    weights = ds.record_weight.values
    np.testing.assert_allclose(weights[:half], weights[half:], rtol=1e-12)
    events = ds.record_event.values
    per_event = [weights[events == e].sum() for e in np.unique(events)]
    np.testing.assert_allclose(per_event, per_event[0], rtol=1e-12)  # each earthquake alike
    free = ds.peak_isolator_disp_over_d_m.values
    np.testing.assert_allclose(free[half:], free[:half], rtol=1e-12)
    np.testing.assert_array_equal(ds.collapse_mode.values[half:], ds.collapse_mode.values[:half])


def test_the_default_ida_knows_each_collapse_intensity_to_the_resolution():
    """The decision model's 0.05 x MCE_R near collapse: the default grid's widest bracket (its
    largest step, 0.5 x MCE_R) after the default bisections."""
    from studies.common.collapse_ida import LEVELS, REFINEMENTS, RESOLUTION, bracket

    assert bracket(np.array(LEVELS), REFINEMENTS) <= RESOLUTION
    assert bracket(np.array(LEVELS), REFINEMENTS - 1) > RESOLUTION  # no round more than needed
    assert bracket(np.array(LEVELS), 0) == 0.5


def test_other_rules_and_a_ductility_below_one_are_refused(tmp_path, capsys):
    for argv, line in ((["--rule", "asce7"], "run it with --rule p695"),
                       (["--mu-t", "0.5"], "--mu-t must be >= 1"),
                       (["--refinements", "-1"], "--refinements must be 0 to 10")):
        assert collapse.main([*argv, "--quick", "--out", str(tmp_path)]) == 2
        err = capsys.readouterr().err
        assert line in err and len(err.strip().splitlines()) == 1
    assert not any(tmp_path.iterdir())


@pytest.fixture(scope="module")
def loss_quick(quick_path, tmp_path_factory):
    """studies.loss --quick on the quick collapse run's fragilities."""
    pytest.importorskip("pelicun")
    from studies import loss

    return run_recipe(loss, ["--quick", "--collapse", str(quick_path / "quick" / "collapse.nc")],
                      tmp_path_factory.mktemp("loss"))


def test_the_loss_archive_holds_the_decision(loss_quick):
    from studies import loss

    ds = loss_quick
    assert_udunits(ds)
    assert_on_variables_page(ds, "loss.nc")
    for name in ("repair_cost", "repair_time", "repair_cost_quantile", "repair_time_quantile",
                 "expected_annual_loss", "annual_rate_contact", "annual_rate_crushed",
                 "annual_rate_collapse", "collapse_probability", "median_repair_cost_mce",
                 "runs_used", "runs_outside_range"):
        assert name in ds, name
    assert ds.repair_cost.dims == ("level", "barrier", "gap_fraction")
    assert ds.attrs["pelicun_version"]
    # every run is counted once, used or collapsed (issue 38: those outside the model's range
    # are used, as computed; they were left out)
    assert (ds.runs_used + ds.runs_collapsed == ds.record.size).all()
    assert (ds.runs_past_accel_limit <= ds.runs_outside_range).all()
    assert (ds.runs_outside_range <= ds.runs_used).all()
    # the repair cost by component group, its acceleration-sensitive share printed
    assert ds.repair_cost_by_group.dims == ("component_group", "level", "barrier",
                                            "gap_fraction")
    assert (ds.repair_cost_by_group >= 0).all() and (ds.repair_cost_by_group[0] > 0).any()
    # the moat's own damage is a group of its own: the realizations' draws of whole runs, whose
    # mean is the items' weighted mean to a slice of the weights (1 / samples) per run, where a
    # stripe has a demand model; the groups sum to the mean repair cost given no collapse
    assert list(ds.component_group.values)[-1] == loss.MOAT_GROUP
    moat = ds.repair_cost_by_group.sel(component_group=loss.MOAT_GROUP)
    modelled = ds.loss_bounded == 0
    exact = ds.moat_damage_cost.sum("moat_item")
    slices = ds.record.size * float(exact.max()) / ds.attrs["samples"]
    np.testing.assert_allclose(moat.where(modelled, 0), exact.where(modelled, 0), rtol=0,
                               atol=slices)
    assert float(exact.max()) > 0  # the quick grid's runs strike the wall
    p_c, replacement = ds.loss_collapse_probability, ds.attrs["replacement_cost"]
    np.testing.assert_allclose(ds.repair_cost_by_group.sum("component_group"),
                               (ds.repair_cost - p_c * replacement) / (1 - p_c), rtol=1e-9)
    assert "(repair_cost_by_group): acceleration-sensitive " in loss.decision_table(ds)
    # how each run collapsed, counted by mode (pipeline.assess.collapse_modes)
    assert ds.collapse_mode.dims == ds.collapsed.dims
    assert_collapse_modes(ds.collapse_mode, ds.collapsed.values)
    by_mode = ds.runs_collapsed_by_mode
    assert by_mode.dims == ("mode",) + ds.runs_collapsed.dims
    assert by_mode.mode.values.tolist() == list(COLLAPSE_MODES[1:])
    assert (by_mode.sum("mode") == ds.runs_collapsed).all()
    for code, mode in enumerate(COLLAPSE_MODES[1:], start=1):
        assert (by_mode.sel(mode=mode) == (ds.collapse_mode == code).sum("record")).all()
    assert json.loads(ds.attrs["collapse_modes"])["collapsed"] == int(ds.collapsed.sum())
    # the quantiles are ordered and the median lies within them
    q = ds.repair_cost_quantile
    assert (q.diff("quantile").fillna(0) >= 0).all()
    # no bumpers: nothing crushed
    assert np.isnan(ds.annual_rate_crushed.sel(barrier=["no wall", "bare wall"])).all()
    assert (ds.annual_rate_contact.sel(barrier="no wall") == 0).all()


def test_annual_values_recompute_from_the_stripes_and_the_hazard(loss_quick):
    from pipeline.assess import hazard

    ds = loss_quick
    curve = hazard.Hazard(ds.hazard_sa.values, ds.hazard_rate.values, "archive")
    sa = ds.level_sa.values
    eal = hazard.mean_annual(sa, ds.repair_cost.values, curve)
    np.testing.assert_allclose(ds.expected_annual_loss.values, eal, rtol=1e-12)
    contact = hazard.mean_annual(sa, ds.contact_probability.values, curve)
    np.testing.assert_allclose(ds.annual_rate_contact.values, contact, rtol=1e-12)
    s_mt = sa[list(ds.level.values).index(1.0)]
    rate = hazard.lognormal_annual(ds.acmr.values * s_mt, ds.beta_total.values, curve)
    np.testing.assert_allclose(ds.annual_rate_collapse.values, rate, rtol=1e-12)


def test_the_expected_annual_loss_carries_its_paired_interval(loss_quick):
    ds = loss_quick
    low, high = ds.expected_annual_loss_interval.sel(interval_bound=[0.025, 0.975]).values
    eal = ds.expected_annual_loss.values
    assert (low <= high).all() and (low > 0).all()
    # the draws resample the earthquakes: some configurations' EAL moves with them
    assert (high > low).any()
    cost = ds.repair_cost_interval
    assert cost.dims == ("interval_bound", "level", "barrier", "gap_fraction")
    assert (cost.diff("interval_bound") >= 0).all() and (cost > 0).all()
    # the ratio to the bare wall at the same gap: 1 for the bare wall, on every draw
    ratio = ds.expected_annual_loss_ratio
    np.testing.assert_allclose(ratio.sel(barrier="bare wall"), 1.0, rtol=1e-12)
    bare = ds.expected_annual_loss_ratio_interval.sel(barrier="bare wall")
    np.testing.assert_allclose(bare, 1.0, rtol=1e-12)
    np.testing.assert_allclose(ratio, eal / ds.expected_annual_loss.sel(barrier="bare wall")
                               .values[None], rtol=1e-12)


def test_the_loss_study_refuses_a_missing_collapse_archive_in_one_line(tmp_path, capsys):
    pytest.importorskip("pelicun")
    from studies import loss

    missing = tmp_path / "none.nc"
    assert loss.main(["--quick", "--collapse", str(missing), "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "--collapse: cannot read" in err and len(err.strip().splitlines()) == 1


def test_the_loss_study_refuses_an_archive_not_of_the_collapse_study(tmp_path, capsys):
    """Issue 40: `loss --collapse` given a sweep's archive ended in a traceback after compute.
    It is refused in one line naming what the file is, before compute, nothing written."""
    pytest.importorskip("pelicun")
    import pipeline
    from studies import loss
    from tests.pipeline.small_sweep import RECORDS, SMALL

    sweep = tmp_path / "sweep.nc"
    pipeline.sweep(RECORDS[:1], **SMALL, quiet=True, out=sweep)
    out = tmp_path / "out"
    assert loss.main(["--quick", "--collapse", str(sweep), "--out", str(out)]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert "is not a collapse study's archive" in line and "studies.collapse" in line
    assert not out.exists()


def test_the_loss_study_refuses_a_collapse_archive_without_its_draws(quick_path, tmp_path,
                                                                     capsys):
    """An archive of an earlier collapse study (no bootstrap draws, which the EAL's interval
    reads) is refused in one line that says to run the collapse study again, nothing
    written."""
    pytest.importorskip("pelicun")
    import xarray as xr

    from studies import loss

    with xr.open_dataset(quick_path / "quick" / "collapse.nc") as ds:
        old = tmp_path / "old.nc"
        ds.drop_vars("collapse_probability_draws").to_netcdf(old)
    out = tmp_path / "out"
    assert loss.main(["--quick", "--collapse", str(old), "--out", str(out)]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert "has no collapse_probability_draws" in line and "studies.collapse again" in line
    assert not out.exists()


def test_the_loss_study_refuses_components_fema_p58_lacks_before_compute(tmp_path, capsys):
    """Issue 40: an inventory naming a component FEMA P-58 does not hold ended in a traceback
    after the simulations. It is refused in one line before any compute, naming it, nothing
    written; the IDs of the default inventory (the advice's example) are all known."""
    pytest.importorskip("pelicun")
    from pipeline.assess import loss as p58
    from studies import loss

    rows = p58.INVENTORY.read_text().splitlines()
    first = rows[1].split(",")[0]
    bad = tmp_path / "inventory.csv"
    bad.write_text("\n".join([rows[0], rows[1].replace(first, "Z.99.99.999", 1), *rows[2:]]))
    out = tmp_path / "out"
    assert loss.main(["--quick", "--inventory", str(bad), "--out", str(out)]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert "--inventory: Z.99.99.999: not in FEMA P-58's fragility database" in line
    assert not out.exists()
    assert p58.unknown_components(p58.read_inventory()) == []


@pytest.mark.parametrize("option, value, named", [("--sm1-g", "0.6", "S_M1_g = 0.9"),
                                                   ("--bound", "upper", "isolator_bound"),
                                                   ("--building", "zeta_sup=0.03",
                                                    "building_zeta_sup = 0.02")])
def test_the_loss_study_refuses_a_collapse_archive_of_another_basis(quick_path, tmp_path,
                                                                    capsys, option, value,
                                                                    named):
    """Another site, bound or building than the collapse archive's: refused before any
    compute, in one line naming the difference (issue 40: a loss at S_M1 0.6 g used the gaps
    and fragilities of a run at 0.9 g); the quick loss run above, on the same options, is
    the advice followed."""
    pytest.importorskip("pelicun")
    from studies import loss

    out = tmp_path / "out"
    archive = quick_path / "quick" / "collapse.nc"
    assert loss.main(["--quick", option, value, "--collapse", str(archive),
                      "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and named in err, err
    assert not out.exists() or not any(out.rglob("*.nc"))


def test_every_configuration_has_an_eal_and_a_bound_says_why(loss_quick):
    """Issue 38: no NaN EAL anywhere. Every run that did not collapse enters the demand model;
    where fewer stand than pelicun's fit needs (MIN_RUNS) the loss given no collapse is taken at
    its upper bound, the replacement (`loss_bounded`): the EAL is then an upper bound
    (`expected_annual_loss_bound` "at most", "<=" in the decision table), the row names those
    stripes, and no other row says so. The quick archive has such rows (3 pairs standing at
    1.5 x MCE_R against a wall at 0.8 D_M)."""
    from pipeline.assess import loss as p58
    from studies import loss

    ds = loss_quick
    assert np.isfinite(ds.expected_annual_loss).all()
    assert np.isfinite(ds.repair_cost).all()
    bounded = ds.loss_bounded.values.astype(bool)
    np.testing.assert_array_equal(bounded, ds.runs_used.values < p58.MIN_RUNS)
    assert bounded.any()  # the rule is exercised
    # a bounded stripe's mean cost: P(C) x replacement + (1 - P(C)) x replacement
    replacement = ds.attrs["replacement_cost"]
    np.testing.assert_allclose(ds.repair_cost.values[bounded], replacement, rtol=1e-12)
    *rows, shares = loss.decision_table(ds).splitlines()[1:]  # the shares last
    assert shares.startswith("the mean repair cost at the MCE_R given no collapse")
    bound = ds.expected_annual_loss_bound.transpose("gap_fraction", "barrier").values.ravel()
    flags = ds.loss_bounded.transpose("gap_fraction", "barrier", "level").values
    assert len(rows) == bound.size
    levels = ds.level.values
    for row, said, few in zip(rows, bound, flags.reshape(bound.size, -1).astype(bool),
                              strict=True):
        assert (said == "at most") == few.any(), row
        assert ("EAL at most: fewer than" in row) == few.any(), row
        assert (" <=" in row.split("M$")[1]) == few.any(), row
        if few.any():
            named = ", ".join(f"{level:g}" for level in levels[few])
            assert f"runs standing at {named} x MCE_R" in row


def test_past_the_models_floor_acceleration_every_sensitive_component_is_at_its_worst():
    """Issue 38: runs past the floor acceleration the model represents (ACCEL_LIMIT, 5 g)
    enter the loss study's demands as computed, which holds because every acceleration-
    sensitive component of the default inventory has the median of its highest damage state
    below it (FEMA P-58's data through pelicun: 4.1 g at most, the water piping's)."""
    pytest.importorskip("pelicun")
    from engine.units import G
    from pipeline.assess import loss as p58
    from pipeline.assess.validity import ACCEL_LIMIT

    fragility, _ = p58._default_data()
    rows = fragility.loc[[r["component"] for r in p58.read_inventory()]]
    sensitive = rows[rows[("Demand", "Type")].str.contains("Acceleration")]
    states = [c for c in sensitive.columns if c[0].startswith("LS") and c[1] == "Theta_0"]
    highest = sensitive[states].apply(lambda r: r.dropna().astype(float).iloc[-1], axis=1)
    assert len(sensitive) >= 5 and (sensitive[("Demand", "Unit")] == "g").all()
    assert highest.max() == pytest.approx(4.1) and highest.max() < ACCEL_LIMIT / G


def test_the_gaps_reach_beyond_the_bearings_capacity_where_they_have_one():
    """0.8 and 1.0 D_M, D_TM and 1.5 D_TM; and for bearings with a displacement capacity (a
    designed triple friction pendulum's 2 d1 + d2 + d3 + ...), BEYOND_CAPACITY times it."""
    import engine
    from pipeline.motions.designed_isolation import designed_isolation
    from studies.common.collapse_ida import BEYOND_CAPACITY, gap_fractions

    designed = designed_isolation(0.9, engine.Building())
    design, building = designed.basis.designs["lower"], designed.basis.buildings["lower"]
    clearance = design.d_tm / design.d_m
    np.testing.assert_array_equal(gap_fractions(design), [0.8, 1.0, clearance, 1.5 * clearance])
    fractions = gap_fractions(design, building)
    assert fractions.size == 5
    assert fractions[-1] * design.d_m == pytest.approx(
        BEYOND_CAPACITY * designed.design.capacity, rel=1e-12)
    paper = engine.Building()  # no capacity: the four gaps
    np.testing.assert_array_equal(gap_fractions(design, paper), gap_fractions(design))


def test_the_loss_figure_draws_the_archive_and_the_groups_stacked(loss_quick):
    """(a)-(c) one curve per barrier from the archive's variables against the gap; (d) against
    the bare wall the repair cost at the MCE_R given no collapse by component group, stacked:
    its top edge is their sum (repair_cost_by_group), each band one group."""
    from studies import loss
    from tests.helpers import drawn

    ds = loss_quick
    fig = loss.plot(ds)
    axes = fig.axes
    gaps = ds.gap.values / CM
    for ax, name, scale in ((axes[0], "median_repair_cost_mce", 1e-6),
                            (axes[1], "expected_annual_loss", 1e-3)):
        lines = drawn(ax)
        assert [label for label, _, _ in lines] == [str(b) for b in ds.barrier.values]
        for (_, x, y), barrier in zip(lines, ds.barrier.values, strict=True):
            np.testing.assert_allclose(x, gaps)
            np.testing.assert_allclose(y, scale * ds[name].sel(barrier=barrier).values)
    bands = axes[3].collections
    groups = ds.repair_cost_by_group.sel(barrier="bare wall").sel(level=1.0, method="nearest")
    assert [b.get_label() for b in bands] == [str(g) for g in ds.component_group.values]
    top = bands[-1].get_paths()[0].vertices[:, 1].max()
    assert top == pytest.approx(1e-6 * float(groups.sum("component_group").max()), rel=1e-12)


def test_the_loss_study_refuses_a_wrong_moat_inventory_in_one_line(tmp_path, capsys):
    """--moat-inventory: a table whose trigger is unknown is refused before any compute, in one
    line naming the option, the file's line and the choices."""
    from studies import loss

    bad = tmp_path / "moat.csv"
    bad.write_text("item,trigger,per,unit_cost,description\nwall,flood,building,1,no\n")
    out = tmp_path / "out"
    assert loss.main(["--quick", "--moat-inventory", str(bad), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and err.startswith("loss: error: --moat-inventory: ")
    assert "line 2: trigger must be one of contact, crushed, beyond_d_tm" in err, err
    assert not out.exists() or not any(out.rglob("*.nc"))


def test_the_loss_study_takes_the_stripes_the_collapse_grid_ran(monkeypatch):
    """Run without --collapse, the loss study takes its stripes at the collapse grid's levels
    from that grid's sweep (the same simulations: checked bit for bit on the quick studies when
    written) and sweeps only the others, each stripe in its place."""
    import types

    import xarray as xr

    import pipeline
    from studies import loss

    def fake(levels, tag):  # a sweep's peaks: 100 x level + tag, per record, level, gap ...
        base = (100 * np.asarray(levels)[None, :, None] + tag) * np.ones((2, 1, 3))
        dims = ("record", "level", "gap")
        data = {}
        for name in loss.PEAKS:
            data["baseline_" + name] = (dims, base)
            data["unconstrained_" + name] = (dims[:2], base[:, :, 0])
            data[name] = (dims + ("n_bumpers",), np.stack([base + 1, base + 2], axis=-1))
        return xr.Dataset(data, coords={"level": list(levels), "n_bumpers": [4, 32]})

    swept = []

    def sweep(pairs, **kw):
        swept.append(list(kw["level"]))
        return fake(kw["level"], 0.5)

    monkeypatch.setattr(pipeline, "sweep", sweep)
    monkeypatch.setattr(loss, "run_options", lambda args: {})
    suite = types.SimpleNamespace(pairs=None, factors=None, building=None)
    args = types.SimpleNamespace(moat="rectangular")
    levels = np.array([0.2, 1.0, 1.25, 1.5])
    grid = fake([0.5, 1.0, 1.5, 2.0], 0.0)
    peaks, _ = loss.run(suite, levels, np.ones(3), [4, 32], args, grid)
    assert swept == [[0.2, 1.25]]  # only the stripes the grid did not run
    got = peaks["n_impacts"]  # (record, level, barrier, gap)
    assert got.shape == (2, 4, 4, 3)
    np.testing.assert_array_equal(got[0, :, 1, 0], [20.5, 100.0, 125.5, 150.0])  # bare wall
    np.testing.assert_array_equal(got[0, :, 3, 0], [22.5, 102.0, 127.5, 152.0])  # 32 bumpers
    # with an archive given (no grid) every stripe is swept
    swept.clear()
    loss.run(suite, levels, np.ones(3), [4, 32], args)
    assert swept == [levels.tolist()]
