"""No result is lost: an archive is replaced only by the same configuration or with --force,
quick runs write beside full ones, a recipe's archive and figures are replaced together or not
at all, and refused runs leave nothing behind.

A toy recipe (a tiny Dataset and figure, no compute) exercises the recipe machinery
(studies.common.recipe) quickly; pipeline.sweep is checked on an 8 s synthetic record.
"""
from __future__ import annotations

import dataclasses

import matplotlib.figure
import numpy as np
import pytest
import xarray as xr

import pipeline
from pipeline.errors import SweepError, said
from studies.common.recipe import Recipe
from tests.pipeline.small_sweep import RECORDS


def toy_compute(args):
    value = 1.0 if args.dt is None else args.dt
    return xr.Dataset({"x": ("n", np.full(3, value), {"units": "1", "long_name": "toy"})},
                      attrs={"title": "toy"})


def toy_plot(ds):
    fig = matplotlib.figure.Figure()
    fig.add_subplot().plot(ds.x.values)
    return fig


TOY = Recipe(name="toy", figure="Fig. 0", summary="a toy", compute=toy_compute, plot=toy_plot,
             check=lambda ds: [], records=None)


def outputs(folder):
    return {p.name: p.read_bytes() for p in folder.iterdir() if p.is_file()}


def test_quick_run_never_replaces_a_full_one(tmp_path):
    full = {"toy.nc": b"the full run", "toy.png": b"its figure", "toy.pdf": b"its pdf"}
    for name, data in full.items():
        (tmp_path / name).write_bytes(data)
    assert TOY.main(["--quick", "--quiet", "--out", str(tmp_path)]) == 0
    assert outputs(tmp_path) == full  # the full run's bytes, untouched
    quick = tmp_path / "quick"
    assert sorted(p.name for p in quick.iterdir()) == ["toy.nc", "toy.pdf", "toy.png"]
    with xr.open_dataset(quick / "toy.nc") as ds:
        assert ds.attrs["quick"] == 1 and "coarse grid" in ds.attrs["title"]


def test_archive_of_another_configuration_is_kept_unless_forced(tmp_path, capsys):
    out = ["--out", str(tmp_path / "toy.nc"), "--quiet"]
    assert TOY.main(out) == 0
    first = outputs(tmp_path)
    assert TOY.main(out) == 0  # the same configuration: replaced, nothing lost
    capsys.readouterr()
    assert TOY.main([*out, "--dt", "2e-3"]) == 2  # another one: refused before compute
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and "--force" in err and "is kept" in err
    assert outputs(tmp_path).keys() == first.keys()
    assert (tmp_path / "toy.nc").read_bytes() == first["toy.nc"]
    assert TOY.main([*out, "--dt", "2e-3", "--force"]) == 0
    with xr.open_dataset(tmp_path / "toy.nc") as ds:
        assert float(ds.x[0]) == 2e-3


def test_a_recipe_writes_a_zarr_store_on_request(tmp_path, capsys):
    out = ["--out", str(tmp_path / "toy.zarr"), "--quiet"]
    assert TOY.main(out) == 0
    assert TOY.main([*out, "--dt", "2e-3"]) == 2  # another configuration: kept, refused
    assert "is kept" in capsys.readouterr().err
    assert TOY.main([*out, "--dt", "2e-3", "--force"]) == 0  # the old store replaced whole
    with xr.open_zarr(tmp_path / "toy.zarr") as ds:
        assert ds.x.values.tolist() == [2e-3] * 3 and ds.x.attrs["units"] == "1"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["toy.pdf", "toy.png", "toy.zarr"]
    assert TOY.main([*out[:2], "--replot"]) == 0


def test_a_file_that_is_not_an_archive_is_kept(tmp_path, capsys):
    (tmp_path / "toy.nc").write_text("my notes")
    assert TOY.main(["--out", str(tmp_path), "--quiet"]) == 2
    assert "cannot identify" in capsys.readouterr().err
    assert (tmp_path / "toy.nc").read_text() == "my notes"


def test_interrupt_while_writing_replaces_nothing(tmp_path, monkeypatch):
    assert TOY.main(["--out", str(tmp_path), "--quiet"]) == 0
    before = outputs(tmp_path)
    real = matplotlib.figure.Figure.savefig

    def interrupted_at_pdf(self, path, *args, **kwargs):
        if kwargs.get("format") == "pdf":
            raise KeyboardInterrupt
        return real(self, path, *args, **kwargs)

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", interrupted_at_pdf)
    assert TOY.main(["--out", str(tmp_path), "--quiet", "--dt", "3e-3", "--force"]) == 130
    assert outputs(tmp_path) == before  # archive and PNG untouched, no temporary file left
    assert not [p for p in tmp_path.iterdir() if p.is_dir()]


def test_refused_runs_leave_nothing_behind(tmp_path, capsys):
    def refused(args):
        raise SweepError("refused")

    assert dataclasses.replace(TOY, compute=refused).main(
        ["--out", str(tmp_path / "new" / "folder"), "--quiet"]) == 2
    with pytest.raises(SweepError, match="unstable"):
        pipeline.sweep(RECORDS, gap=0.1, dt=0.05, out=tmp_path / "sweep" / "x.nc", quiet=True)
    assert dataclasses.replace(TOY, compute=refused).main(
        ["--out", str(tmp_path / "x.zarr"), "--quiet"]) == 2
    assert "refused" in capsys.readouterr().err
    assert not list(tmp_path.iterdir())


def test_sweep_archive_replaced_only_by_the_same_sweep(tmp_path):
    out = tmp_path / "s.nc"
    small = dict(gap=[0.08, 0.12], thickness=0.03, dt=0.004, quiet=True, out=out)
    first = pipeline.sweep(RECORDS, **small)
    assert len(first.attrs["configuration_key"]) == 64
    pipeline.sweep(RECORDS, **small)  # the same sweep: replaced
    with pytest.raises(SweepError, match="another configuration.*is kept") as refused:
        pipeline.sweep(RECORDS, **{**small, "gap": [0.08, 0.14]})
    # advice in its reader's spelling: Python's arguments here, the options on the command line
    assert "Give force=True to replace it, or another out" in str(refused.value)
    assert "Give --force to replace it, or another --out" in said(refused.value)
    with xr.open_dataset(out) as ds:
        np.testing.assert_array_equal(ds.gap, [0.08, 0.12])
    pipeline.sweep(RECORDS, **{**small, "gap": [0.08, 0.14]}, force=True)
    with xr.open_dataset(out) as ds:
        np.testing.assert_array_equal(ds.gap, [0.08, 0.14])


def test_ctrl_c_anywhere_says_what_is_kept_and_how_to_resume(tmp_path, capsys):
    def stopped_early(args):
        raise KeyboardInterrupt

    def stopped_after_a_sweep(args):
        pipeline.sweep(RECORDS, gap=[0.08, 0.12], thickness=0.03, quiet=True,
                       work_dir=args.work_dir)
        raise KeyboardInterrupt

    out = ["--out", str(tmp_path), "--quiet"]
    assert dataclasses.replace(TOY, compute=stopped_early).main(out) == 130
    assert capsys.readouterr().err == ("toy: interrupted before any simulation finished: "
                                       "nothing to keep; run the same command again to start "
                                       "over\n")
    assert dataclasses.replace(TOY, compute=stopped_after_a_sweep).main(out) == 130
    assert capsys.readouterr().err == (f"toy: interrupted: 4 finished simulations kept in "
                                       f"{tmp_path / 'toy.nc.work'}; run the same command "
                                       "again to resume\n")


@pytest.mark.parametrize("name", ["x.nc", "x.zarr"])
def test_no_cluster_leaves_nothing_behind(tmp_path, name):
    with pytest.raises(SweepError, match="127.0.0.1:9"):
        pipeline.sweep(RECORDS, gap=0.1, thickness=0.03, scheduler="tcp://127.0.0.1:9",
                       out=tmp_path / "new" / name, quiet=True)
    assert not list(tmp_path.iterdir())
