"""The main recipe, gap_size (Figs. 14-15), in --quick form: archive, figure, paper check."""
import numpy as np
import pytest
import xarray as xr

from studies import gap_size
from studies.common.recipe import verdicts
from tests.helpers import assert_udunits


@pytest.fixture(scope="module")
def quick_run(tmp_path_factory, records_dir_args):
    out = tmp_path_factory.mktemp("gap_size")
    args = ["--quick", "--workers", "1", "--quiet", "--out", str(out), *records_dir_args]
    assert gap_size.main(args) == 0
    return out / "quick"  # a quick run's outputs never replace a full run's


def test_archive_is_labelled_and_complete(quick_run):
    with xr.open_dataset(quick_run / "gap_size.nc") as ds:
        assert dict(ds.sizes) == {"record": 4, "gap": 4, "floor": 5, "story": 4}
        np.testing.assert_allclose(ds.gap, [0.15, 0.25, 0.35, 0.45])
        assert ds.gap.attrs["units"] == "m"
        assert ds.thickness.item() == 0.05 and ds.n_bumpers.item() == 4
        for name in ("peak_total_accel", "peak_interstory_drift", "peak_isolator_disp",
                     "max_indentation", "max_impact_force", "baseline_peak_total_accel",
                     "amplification_total_accel", "amplification_interstory_drift",
                     "unconstrained_peak_isolator_disp"):
            assert not ds[name].isnull().any(), name
            assert "units" in ds[name].attrs, name
        ratio = ds.peak_total_accel / ds.baseline_peak_total_accel
        np.testing.assert_allclose(ds.amplification_total_accel, ratio)
        assert "paper 5.1" in ds.attrs["paper_check"]
        assert [v["conclusion"] for v in verdicts(ds)] == ["5.1", "5.1"]
        assert_udunits(ds)
        assert ds.attrs["recipe"] == "gap_size" and ds.attrs["quick"] == 1


def test_figure_files_and_replot(quick_run):
    png, pdf = quick_run / "gap_size.png", quick_run / "gap_size.pdf"
    assert png.stat().st_size > 10_000 and pdf.stat().st_size > 10_000
    png.unlink()
    assert gap_size.main(["--replot", "--out", str(quick_run)]) == 0
    assert png.exists()


def test_help_and_bad_input(tmp_path, capsys):
    with pytest.raises(SystemExit) as exit_info:
        gap_size.main(["--help"])
    assert exit_info.value.code == 0
    assert "15-45 cm" in capsys.readouterr().out
    assert gap_size.main(["--replot", "--out", str(tmp_path)]) == 2
    assert gap_size.main(["--quick", "--records", "no-such-record", "--workers", "1",
                          "--out", str(tmp_path)]) == 2
    assert "no-such-record" in capsys.readouterr().err
