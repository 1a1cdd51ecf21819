"""Large variables' chunks compressed on every core: the file is netCDF4's, shuffled and
deflated as HDF5 declares it, and reads back the arrays bit for bit."""
import h5py
import numpy as np
import pytest
import xarray as xr

from pipeline import parallel_deflate
from pipeline.archive import to_netcdf
from pipeline.parallel_deflate import chunk_shape, parallel_variables, write_chunks


def test_a_chunk_is_whole_trailing_dimensions_and_a_part_of_the_next():
    # a sweep's (record, gap, wall_k, floor) peaks: 5 floors x 8 bytes x 1000 = 40 kB a gap,
    # 26 gaps to a megabyte
    assert chunk_shape((1, 1000, 1000, 5), 8) == (1, 26, 1000, 5)
    assert chunk_shape((3, 7), 8) == (3, 7)  # smaller than a chunk: one chunk
    assert chunk_shape((10, 10, 10), 1, target=250) == (2, 10, 10)
    assert chunk_shape((4, 3000), 8, target=1000) == (1, 125)


def _sweep_like(rng) -> xr.Dataset:
    """Peaks with NaN (a member outside the model), counts and flags, on dimensions that are
    not multiples of the chunks (edge chunks padded), and a small variable."""
    shape = (2, 37, 29, 5)
    peaks = rng.standard_normal(shape) * 1e3
    peaks[0, 3, 4] = np.nan
    return xr.Dataset(
        {"peak": (("record", "gap", "wall_k", "floor"), peaks, {"units": "m s-2"}),
         "n_impacts": (("record", "gap", "wall_k"), rng.integers(0, 40, shape[:3]),
                       {"units": "1"}),
         "flag": (("record", "gap", "wall_k"), rng.integers(0, 2, shape[:3]).astype(np.int8),
                  {"units": "1"}),
         "small": (("record",), [1.5, 2.5], {"units": "m"})},
        coords={"gap": ("gap", np.linspace(0.05, 0.5, shape[1]), {"units": "m"})},
        attrs={"title": "parallel deflate"})


@pytest.fixture
def small_threshold(monkeypatch):
    monkeypatch.setattr(parallel_deflate, "PARALLEL_BYTES", 4096)
    monkeypatch.setattr(parallel_deflate, "CHUNK_BYTES", 2048)


def test_the_archive_reads_back_every_number_and_attribute(tmp_path, small_threshold):
    ds = _sweep_like(np.random.default_rng(3))
    assert parallel_variables(ds) == ["peak", "n_impacts"]  # the flags and `small` too small
    to_netcdf(ds, tmp_path / "parallel.nc")
    with h5py.File(tmp_path / "parallel.nc", "r") as f:  # the threads wrote the chunks
        assert f["peak"].chunks == chunk_shape((2, 37, 29, 5), 8, target=2048) == (1, 1, 29, 5)
        assert (f["peak"].compression, f["peak"].compression_opts, f["peak"].shuffle) \
            == ("gzip", 4, True)
        assert f["n_impacts"].chunks == (1, 8, 29)
    back = xr.open_dataset(tmp_path / "parallel.nc")
    plain = tmp_path / "plain.nc"
    ds.to_netcdf(plain, engine="netcdf4")
    serial = xr.open_dataset(plain)
    for name, var in ds.variables.items():
        np.testing.assert_array_equal(back[name].values, var.values, err_msg=name)
        assert back[name].dtype == var.dtype, name
        assert back[name].attrs == serial[name].attrs, name  # _FillValue as xarray's own
    assert back.attrs == ds.attrs


def test_a_variable_of_several_chunks_reads_back_on_any_number_of_threads(tmp_path,
                                                                         small_threshold):
    data = np.random.default_rng(5).standard_normal((3, 41, 17))
    ds = xr.Dataset({"x": (("a", "b", "c"), data, {"units": "m"})})  # no coordinates
    for threads in (1, 3):
        path = tmp_path / f"t{threads}.nc"
        parallel_deflate.write(ds, path, {"x": {"zlib": True, "complevel": 1}},
                               threads=threads)
        with h5py.File(path, "r") as f:
            assert (f["x"].chunks, f["x"].compression_opts) == ((1, 15, 17), 1)  # 41 = 15+15+11
        back = xr.open_dataset(path)
        np.testing.assert_array_equal(back["x"].values, data)
        assert back["x"].attrs == {"units": "m"} and back.sizes == ds.sizes


def test_a_variable_not_stored_deflated_is_refused(tmp_path):
    ds = xr.Dataset({"x": (("a",), np.arange(1000.0))})
    ds.to_netcdf(tmp_path / "raw.nc", encoding={"x": {"chunksizes": (100,)}})
    with pytest.raises(ValueError, match="x: stored as float64 .*expected the declaration"):
        write_chunks(tmp_path / "raw.nc", ds, ["x"])


def test_a_variable_whose_stored_numbers_differ_is_left_to_xarray(tmp_path, small_threshold):
    ds = _sweep_like(np.random.default_rng(7))
    ds["peak"].encoding = {"scale_factor": 0.5, "dtype": "int32"}
    assert parallel_variables(ds) == ["n_impacts"]
    to_netcdf(ds, tmp_path / "scaled.nc")
    back = xr.open_dataset(tmp_path / "scaled.nc")
    np.testing.assert_allclose(back["peak"].values, ds["peak"].values, atol=0.25)
    np.testing.assert_array_equal(back["n_impacts"].values, ds["n_impacts"].values)


def test_without_h5py_netcdf4_writes_it_all(tmp_path, small_threshold, monkeypatch):
    import builtins

    real_import = builtins.__import__

    def no_h5py(name, *args, **kwargs):
        if name == "h5py":
            raise ImportError("no h5py")
        return real_import(name, *args, **kwargs)

    ds = _sweep_like(np.random.default_rng(9))
    monkeypatch.setattr(builtins, "__import__", no_h5py)
    to_netcdf(ds, tmp_path / "serial.nc")
    monkeypatch.undo()
    back = xr.open_dataset(tmp_path / "serial.nc")
    for name, var in ds.data_vars.items():
        np.testing.assert_array_equal(back[name].values, var.values, err_msg=name)
