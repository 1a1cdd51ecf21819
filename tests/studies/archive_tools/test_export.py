"""`bumpers export` (studies/archive_tools/export.py) on a small sweep archive (conftest.py):
the CSV holds the archive's values, the pelicun sample pelicun's columns and units row (read
back by pelicun when it is installed). (`bumpers plot`: test_plot.py; bad input: test_table.py.)"""
import importlib.util

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from pipeline.assess.validity import FLAGS
from studies import cli
from studies.archive_tools import export

HEIGHT = 3.5  # m, every story


def check_table(table: pd.DataFrame, ds: xr.Dataset):
    assert list(table.columns[:4]) == ["record", "gap [m]", "n_bumpers", "block"]
    assert table.block.value_counts().to_dict() == {"bumpers": 4, "baseline": 2,
                                                    "unconstrained": 1}
    for _, row in table.iterrows():
        at = {"record": row["record"]}
        prefix = {"bumpers": "", "baseline": "baseline_", "unconstrained": "unconstrained_"}
        prefix = prefix[row.block]
        if row.block != "unconstrained":
            at["gap"] = row["gap [m]"]
        if row.block == "bumpers":
            at["n_bumpers"] = int(row["n_bumpers"])
        else:
            assert pd.isna(row["n_bumpers"])  # the references run no bumpers
        for floor in ds.floor.values:
            assert row[f"peak_total_accel_floor{floor} [m s-2]"] == \
                ds[prefix + "peak_total_accel"].sel({**at, "floor": floor}).item()
        for story in ds.story.values:
            assert row[f"peak_interstory_drift_story{story} [m]"] == \
                ds[prefix + "peak_interstory_drift"].sel({**at, "story": story}).item()
        assert row["max_impact_force [N]"] == ds[prefix + "max_impact_force"].sel(at).item()
        for flag in FLAGS:  # a run outside the model's range is marked in the table too
            if prefix + flag in ds:
                assert row[flag] == ds[prefix + flag].sel(at).item()
        assert row["n_impacts"] == ds[prefix + "n_impacts"].sel(at).item()
        ratio = row["amplification_total_accel_floor4"]
        if row.block == "bumpers":
            assert ratio == ds.amplification_total_accel.sel({**at, "floor": 4}).item()
        else:
            assert pd.isna(ratio)


@pytest.mark.parametrize("suffix", [".nc", ".zarr"])
def test_csv_holds_the_archive_values(archive, tmp_path, suffix, capsys):
    path, ds = archive
    out = tmp_path / "peaks.csv"
    assert cli.main(["export", str(path.with_suffix(suffix)), "--csv", str(out)]) == 0
    assert "wrote" in capsys.readouterr().out
    table = pd.read_csv(out, float_precision="round_trip")
    check_table(table, ds)
    # the validity flags travel with the peaks: every block's, and some run is flagged here
    assert {"invalid_floor_accel", "invalid_bumper_stress"} <= set(table.columns)
    assert table["invalid_bumper_stress"].sum() > 0
    # and every result the engine declares (issue 40: the residuals were left out)
    for name in ("peak_isolator_force", "peak_story_shear", "peak_floor_velocity",
                 "residual_isolator_disp", "residual_interstory_drift"):
        assert any(c.startswith(name) for c in table.columns), name


def test_csv_of_one_block_at_one_value(archive, tmp_path):
    path, ds = archive
    out = tmp_path / "peaks.csv"
    assert export.main([str(path), "--csv", str(out), "--block", "bumpers",
                        "--sel", "n_bumpers=8"]) == 0
    table = pd.read_csv(out, float_precision="round_trip")
    assert len(table) == 2 and set(table.block) == {"bumpers"}
    np.testing.assert_array_equal(table["peak_isolator_disp [m]"],
                                  ds.peak_isolator_disp.sel(n_bumpers=8).values.ravel())


def test_pelicun_sample_columns_and_units_row(archive, tmp_path):
    path, ds = archive
    out = tmp_path / "demands.csv"
    assert export.main([str(path), "--pelicun", str(out), "--story-height-m", str(HEIGHT),
                        "--sel", "gap=0.1"]) == 0
    lines = out.read_text().splitlines()
    floors, stories = ds.sizes["floor"], ds.sizes["story"]
    assert lines[0].split(",") == ["", *(f"1-PFA-{f}-1" for f in range(floors)),
                                   *(f"1-PID-{s}-1" for s in range(1, stories + 1))]
    assert lines[1].split(",") == ["Units", *["g"] * floors, *["rad"] * stories]
    sample = pd.read_csv(out, index_col=0, skiprows=[1], float_precision="round_trip")
    assert list(sample.index) == [0, 1]  # one row per run: n_bumpers 4 and 8
    np.testing.assert_allclose(sample["1-PFA-4-1"], ds.peak_total_accel.sel(
        gap=0.1, floor=4).values.ravel() / export.PELICUN_G, rtol=1e-14)
    np.testing.assert_allclose(sample["1-PID-1-1"], ds.peak_interstory_drift.sel(
        gap=0.1, story=1).values.ravel() / HEIGHT, rtol=1e-14)


@pytest.mark.skipif(importlib.util.find_spec("pelicun") is None,
                    reason="pelicun (an optional extra) is not installed")
def test_pelicun_reads_the_sample_back(archive, tmp_path):
    from pelicun.assessment import Assessment

    path, ds = archive
    out = tmp_path / "demands.csv"
    assert export.main([str(path), "--pelicun", str(out), "--story-height-m", str(HEIGHT)]) == 0
    assessment = Assessment({"PrintLog": False})
    assessment.demand.load_sample(str(out))
    sample = assessment.demand.sample  # pelicun's SI: m/s^2 and rad
    np.testing.assert_allclose(sample["PFA"]["4"]["1"].values,
                               ds.peak_total_accel.sel(floor=4).values.ravel(), rtol=1e-12)
    np.testing.assert_allclose(sample["PID"]["2"]["1"].values,
                               ds.peak_interstory_drift.sel(story=2).values.ravel() / HEIGHT,
                               rtol=1e-12)
