"""studies.suite --quick on a handful of records: the archive, its statistics, the
conclusions table, and a suite member against a direct sweep of the same scaled record."""
from __future__ import annotations

import json

import numpy as np
import pytest

import pipeline
from studies import suite
from studies._paper import FIG21_WALL_KS, THICKNESS
from studies._recipe import verdicts
from tests.helpers import assert_udunits, run_recipe

RECORDS = ["kobe", "pacoima", "sylmar_converter", "olive_view", "RSN1690:360"]


@pytest.fixture(scope="module")
def archive(tmp_path_factory):
    return run_recipe(suite, ["--quick", "--records", *RECORDS],
                      tmp_path_factory.mktemp("suite"))


def test_dims_units_and_left_out_records(archive):
    ds = archive
    assert dict(ds.sizes) == {"record": 4, "gap_ratio": 5, "n_bumpers": 2, "wall_k": 3,
                              "floor": 5, "story": 4, "response": 3, "quantile": 3}
    assert ds.amplification.dims == ("response", "record", "gap_ratio", "n_bumpers", "wall_k")
    np.testing.assert_allclose(ds.gap.values, ds.gap_ratio.values * 0.30, rtol=1e-12)
    assert ds.gap.dims == ("gap_ratio",)
    assert_udunits(ds)
    for name in ("record_scale", "record_unscaled_pga", "record_pga", "record_pgv",
                 "record_pulse", "record_sd_iso"):
        assert ds[name].dims == ("record",), name
    # the weak record would need ~54x: reported and left out, never kept
    (left,) = json.loads(ds.attrs["records_left_out"])
    assert left["record"] == "Northridge05-SylmarCountyHospitalGrounds-360"
    assert left["factor_needed"] > 5
    assert not any(r.startswith("Northridge05") for r in ds.record.values.tolist())
    np.testing.assert_allclose(ds.record_pga / ds.record_unscaled_pga, ds.record_scale,
                               rtol=1e-12)


def test_statistics_are_consistent(archive):
    ds = archive
    for name in ("fraction_helped", "fraction_crushed"):
        assert float(ds[name].min()) >= 0 and float(ds[name].max()) <= 1, name
    q = ds.amplification_quantile
    assert np.all(q.sel(quantile=0.16) <= q.sel(quantile=0.5))
    assert np.all(q.sel(quantile=0.5) <= q.sel(quantile=0.84))
    # recomputed by hand from the peaks: largest floor acceleration, with over without
    ratio = (ds.peak_total_accel.max("floor") / ds.baseline_peak_total_accel.max("floor"))
    np.testing.assert_array_equal(ds.amplification.sel(response="floor_accel").values,
                                  ratio.transpose("record", ...).values)
    helped = (ratio < 1).mean("record").transpose("gap_ratio", ...)
    np.testing.assert_array_equal(
        ds.fraction_helped.sel(response="floor_accel").transpose("gap_ratio", ...).values,
        helped.values)
    crushed = (ds.max_indentation > 0.04).mean("record").transpose("gap_ratio", ...)
    np.testing.assert_array_equal(ds.fraction_crushed.transpose("gap_ratio", ...).values,
                                  crushed.values)
    # the narrowest gap is the one bumpers help most: more records helped than at gap = D
    base = ds.fraction_helped.sel(response="base_accel", n_bumpers=4, wall_k=1.5e9)
    assert float(base.sel(gap_ratio=0.5)) > float(base.sel(gap_ratio=1.0))


def test_conclusions_table(archive):
    table = verdicts(archive)
    assert [v["conclusion"] for v in table] == ["5.1", "5.1", "5.1", "5.1", "5.2", "5.3",
                                                "5.4", "5.4", "5.5", "5.6", "6", "6"]
    for v in table:
        share = v["numbers"].get("fraction_of_records")
        if v["verdict"] == "not tested":
            assert share is None
            continue
        assert 0 <= share <= 1 and v["numbers"]["records_counted"] >= 1
        assert v["verdict"] == ("agrees" if share >= suite.HOLDS else "differs")
        assert f"{share:.0%} of {v['numbers']['records_counted']} records" in v["finding"]
    # the softer wall helps under every record that crushes the bumpers (Fig. 21's finding)
    assert table[8]["numbers"]["fraction_of_records"] == 1.0


def test_member_equals_a_direct_sweep(archive):
    """The suite's member = pipeline.sweep of the scaled record named by its spec string,
    at the same gap: the same numbers, bit for bit."""
    ds = archive
    name = str(ds.record.values[1])  # e.g. "pacoima*1.06547"
    assert name.startswith("pacoima*")
    gap = float(ds.gap.values[0])
    direct = pipeline.sweep([name], gap=gap, thickness=THICKNESS, n_bumpers=[4, 32],
                            wall_k=list(FIG21_WALL_KS), baseline=True, quiet=True)
    member = ds.sel(record=name).isel(gap_ratio=0)
    for var in ("peak_total_accel", "peak_interstory_drift", "max_indentation",
                "baseline_peak_total_accel"):
        np.testing.assert_array_equal(member[var].values, direct[var].sel(record=name).values)
    assert direct.record_scale.item() == float(name.split("*")[1])


def test_maps_tell_no_contact_and_ties_from_harm(archive):
    """The maps of records helped: cells where nothing touches the wall (told by the impact
    counts) are their own hatched 'no contact' category, not harm; an exact tie with contact
    (amplification 1) is neither harm nor help."""
    from matplotlib.colors import to_rgba

    ds = archive.copy(deep=True)
    # a tie at the narrowest gap, where every record hits the bare wall (gap < D)
    tie = {"response": "floor_accel", "gap_ratio": 0.5, "n_bumpers": 4, "wall_k": 1.5e9}
    assert bool((ds.baseline_n_impacts.sel(gap_ratio=0.5) > 0).all())
    ds["amplification"].loc[tie] = 1.0
    touches = (ds.n_impacts > 0) | (ds.baseline_n_impacts > 0)
    no_contact = ~touches.sel(wall_k=1.5e9).any("record").transpose("n_bumpers", "gap_ratio")
    assert no_contact.any() and not no_contact.all()  # the quick grid has both kinds of cell
    fig = suite.plot(ds)
    try:
        bumper_map = next(ax for ax in fig.axes if ax.images
                          and ax.get_ylabel() == "bumpers per side")
        (image,) = bumper_map.images
        np.testing.assert_array_equal(np.ma.getmaskarray(image.get_array()), no_contact.values)
        hatched = {(round(p.get_x() + p.get_width() / 2, 6), round(p.get_y() + 0.5))
                   for p in bumper_map.patches if p.get_hatch()}
        assert hatched == {(float(ds.gap_ratio[c]), r)
                           for r, c in zip(*np.nonzero(no_contact.values), strict=True)}
        rgba = image.to_rgba(image.get_array())
        row, col = list(ds.n_bumpers.values).index(4), list(ds.gap_ratio.values).index(0.5)
        neutral, harm = image.cmap(0.5), image.cmap(0.0)
        assert tuple(rgba[row, col]) == pytest.approx(neutral, abs=1e-2)
        assert tuple(rgba[row, col]) != pytest.approx(harm, abs=1e-2)
        texts = [(t.get_text(), h) for ax in fig.axes if ax.get_legend()
                 for t, h in zip(ax.get_legend().get_texts(),
                                 ax.get_legend().legend_handles, strict=True)]
        (handle,) = [h for text, h in texts if text == "no contact"]
        assert handle.get_hatch() and to_rgba(handle.get_facecolor()) != to_rgba(harm)
    finally:
        import matplotlib.pyplot as plt

        plt.close(fig)
