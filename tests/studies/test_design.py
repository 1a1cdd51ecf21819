"""studies.design --quick: the search's archive, its choice, and the choice against a direct
sweep of the same configuration."""
from __future__ import annotations

import numpy as np
import pytest

import pipeline
from studies import design
from studies._recipe import verdicts
from tests.helpers import assert_udunits, run_recipe

RECORDS = ["kobe", "pacoima", "sylmar_converter", "olive_view"]


@pytest.fixture(scope="module")
def archive(tmp_path_factory):
    return run_recipe(design, ["--quick", "--records", *RECORDS],
                      tmp_path_factory.mktemp("design"))


def test_archive(archive):
    ds = archive
    assert ds.peak_floor_accel.dims == ("record", "candidate")
    assert ds.sizes["record"] == 4 and set(np.unique(ds.stage.values)) == {1, 2}
    assert_udunits(ds)
    assert 0 <= float(ds.fraction_crushed.min()) and float(ds.fraction_crushed.max()) <= 1
    assert np.all(ds.p16_peak_floor_accel <= ds.median_peak_floor_accel)
    assert np.all(ds.median_peak_floor_accel <= ds.p84_peak_floor_accel)
    # statistics recomputed from the per-record values
    np.testing.assert_array_equal(ds.median_peak_floor_accel.values,
                                  np.median(ds.peak_floor_accel.values, axis=0))
    np.testing.assert_array_equal(ds.fraction_crushed.values, ds.crushed.values.mean(axis=0))
    assert len(verdicts(ds)) == 3


def test_choice_is_the_best_feasible(archive):
    ds = archive
    chosen = int(ds.attrs["chosen_candidate"])
    feasible = ds.fraction_crushed.values <= 1 - ds.attrs["uncrushed_fraction_required"]
    assert feasible[chosen] and int(ds["rank"][chosen]) == 1
    med = ds.median_peak_floor_accel.values
    assert med[chosen] == med[feasible].min()
    assert np.all(ds["rank"].values[~feasible] == 0)
    # and it beats the bare wall, which its median amplification says
    assert float(ds.median_amplification[chosen]) < 1


def test_choice_equals_a_direct_sweep(archive):
    ds = archive
    chosen = int(ds.attrs["chosen_candidate"])
    config = {name: float(ds[name][chosen]) for name in design.SEARCHED}
    config["n_bumpers"] = int(config["n_bumpers"])
    direct = pipeline.sweep(ds.record.values.tolist(), gap=float(ds.attrs["design_gap"]),
                            quiet=True, **config)
    np.testing.assert_array_equal(direct.peak_total_accel.max("floor").values,
                                  ds.peak_floor_accel.values[:, chosen])


@pytest.mark.parametrize("argv, match", [
    (["--uncrushed", "1.5"], "--uncrushed"),
    (["--building", "k9=1"], "--building"),
    (["--building", "k2=abc"], "not a number"),
])
def test_bad_options(argv, match, tmp_path, capsys):
    assert design.main([*argv, "--quick", "--records", "pacoima", "--out",
                        str(tmp_path)]) == 2
    assert match in capsys.readouterr().err
