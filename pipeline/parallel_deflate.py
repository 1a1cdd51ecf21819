"""A large archive's variables written with their chunks compressed on every core.

netCDF4 (HDF5) compresses a variable's chunks one after another in the thread that writes it:
a 10^6-member sweep's 230 MB of peaks took 4 s at zlib level 4 (the largest part of the
sweep's time beside its kernel on a GPU), while the machine's other cores waited. The chunks
are independent. Here each is shuffled and deflated as HDF5's shuffle and deflate filters do
(the filters netCDF4 declares on the variable, so every reader inflates them as its own) in a
pool of threads (zlib releases the GIL while it compresses), and stored as it is (HDF5's
direct chunk write, through h5py). The file stays netCDF4's own: xarray writes the rest,
netCDF4 declares the large variables as xarray would (`write`), and only their chunks are
stored past netCDF4. The numbers read back are the array's, bit for bit
(tests/pipeline/test_parallel_deflate.py).
"""
from __future__ import annotations

import functools
import itertools
import os
import tempfile
import zlib
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import xarray as xr

PARALLEL_BYTES = 8 << 20
"""A numeric variable this large (bytes) or larger is written by `write_chunks`; a smaller one
as netCDF4 writes it (an archive of small variables gains nothing from the threads)."""

CHUNK_BYTES = 1 << 20
"""A chunk's size before compression (bytes), about: 1 MB chunks give a 10^6-member sweep's
largest variable 40 of them to share among the threads, and a reader of one member inflates
1 MB."""

VALUE_ENCODINGS = ("dtype", "scale_factor", "add_offset", "_FillValue", "missing_value",
                   "calendar", "units", "_Unsigned")
"""Encodings that make the numbers xarray stores differ from the array's: a variable carrying
one (read from an archive that declared it) is left to xarray."""


def parallel_variables(ds: xr.Dataset) -> list[str]:
    """The data variables of `ds` that `write_chunks` writes: NumPy arrays of numbers stored as
    they are (no value-changing encoding), PARALLEL_BYTES or larger."""
    return [name for name, var in ds.data_vars.items()
            if isinstance(var.data, np.ndarray) and var.dtype.kind in "fiu"
            and var.nbytes >= PARALLEL_BYTES and var.ndim
            and not any(key in var.encoding for key in VALUE_ENCODINGS)]


def chunk_shape(shape: tuple[int, ...], itemsize: int,
                target: int | None = None) -> tuple[int, ...]:
    """A chunk of about `target` bytes (default CHUNK_BYTES) for an array of `shape` (items
    of `itemsize` bytes): whole trailing dimensions while they fit, a part of the next one, 1
    before it, so that a chunk is one contiguous block of the C-ordered array."""
    target = CHUNK_BYTES if target is None else target
    chunks: list[int] = []
    size = itemsize
    for n in reversed(shape):
        take = max(1, min(n, target // size))
        chunks.insert(0, take)
        size *= take
        if take < n:
            return (1,) * (len(shape) - len(chunks)) + tuple(chunks)
    return tuple(chunks)


def write(ds: xr.Dataset, path, encoding: dict, threads: int | None = None) -> None:
    """Write `ds` to the netCDF4 file `path` (not atomic), its `parallel_variables` compressed
    on `threads` threads (default: every core), the others by xarray with `encoding` (their
    zlib), the parallel ones at its zlib level (default 4).

    xarray writes the dataset without the large variables; each is then declared as xarray
    declares it (its attributes and fill value are read from a one-element copy xarray writes
    beside), chunked (chunk_shape), shuffled and deflated, and its chunks stored
    (write_chunks). ImportError without h5py, OSError or ValueError where the file cannot be
    written so: the caller writes it all with xarray instead."""
    import netCDF4

    large = parallel_variables(ds)
    rest = {name: value for name, value in encoding.items() if name not in large}
    ds.drop_vars(large).to_netcdf(path, engine="netcdf4", format="NETCDF4", encoding=rest)
    with tempfile.TemporaryDirectory() as folder:
        twin_path = os.path.join(folder, "twin.nc")
        twin = ds[large].isel({dim: slice(0, 1) for name in large for dim in ds[name].dims})
        twin.to_netcdf(twin_path, engine="netcdf4", format="NETCDF4")
        with netCDF4.Dataset(twin_path) as twin_file, netCDF4.Dataset(path, "r+") as nc:
            for name in large:
                _declare(nc, twin_file[name], ds, name,
                         int(encoding.get(name, {}).get("complevel", 4)))
    write_chunks(path, ds, large, threads)


def _declare(nc, twin, ds: xr.Dataset, name: str, level: int) -> None:
    """Declare variable `name` of `ds` in the open netCDF4 file `nc` as xarray declared its
    one-element `twin` (type, dimensions, attributes, fill value), chunked and deflated at
    `level` with HDF5's shuffle; no data written."""
    for dim in twin.dimensions:
        if dim not in nc.dimensions:  # a dimension only the large variables have
            nc.createDimension(dim, ds.sizes[dim])
    attrs = {key: twin.getncattr(key) for key in twin.ncattrs()}
    variable = nc.createVariable(name, twin.datatype, twin.dimensions, zlib=True,
                                 complevel=level, shuffle=True,
                                 chunksizes=chunk_shape(ds[name].shape, ds[name].dtype.itemsize),
                                 fill_value=attrs.pop("_FillValue", None))
    variable.setncatts(attrs)


def _shuffled_deflate(block: np.ndarray, level: int) -> bytes:
    """One chunk as HDF5 stores it through the shuffle and deflate filters: the items' first
    bytes, then their second bytes, ..., zlib-compressed at `level`."""
    raw = np.ascontiguousarray(block).view(np.uint8).reshape(-1, block.dtype.itemsize)
    return zlib.compress(np.ascontiguousarray(raw.T).tobytes(), level)


def _compressed_chunk(data: np.ndarray, shape: tuple[int, ...], level: int,
                      origin: tuple[int, ...]) -> bytes:
    """The chunk of `data` at `origin`, padded with zeros to the full `shape` at the array's
    far edges (HDF5 stores every chunk whole), shuffled and deflated."""
    block = data[tuple(slice(o, o + n) for o, n in zip(origin, shape, strict=True))]
    if block.shape != shape:
        full = np.zeros(shape, dtype=data.dtype)
        full[tuple(slice(0, n) for n in block.shape)] = block
        block = full
    return _shuffled_deflate(block, level)


def _cores() -> int:
    """The cores this process may run on."""
    affinity = getattr(os, "sched_getaffinity", None)
    return len(affinity(0)) if affinity else (os.cpu_count() or 1)


def write_chunks(path, ds: xr.Dataset, names, threads: int | None = None) -> None:
    """Store the numbers of the variables `names` of `ds` into the netCDF4 file `path`, which
    declares them (`write`), chunked, with HDF5's shuffle and deflate filters: every chunk
    compressed on `threads` threads (default: every core), then written as it is. ValueError
    if a variable's storage in the file is not that."""
    import h5py

    with h5py.File(path, "r+") as f, \
            ThreadPoolExecutor(threads or _cores()) as pool:
        for name in names:
            data, stored = ds[name].values, f[name]
            if stored.compression != "gzip" or not stored.shuffle or stored.chunks is None \
                    or stored.dtype != data.dtype or stored.shape != data.shape:
                raise ValueError(f"{name}: stored as {stored.dtype} {stored.shape}, chunks "
                                 f"{stored.chunks}, {stored.compression}, shuffle "
                                 f"{stored.shuffle}; expected the declaration of a "
                                 f"{data.dtype} {data.shape} array, shuffled and deflated")
            level, shape = stored.compression_opts, stored.chunks
            origins = list(itertools.product(*(range(0, n, c)
                                               for n, c in zip(data.shape, shape, strict=True))))
            compressed = pool.map(functools.partial(_compressed_chunk, data, shape, level),
                                  origins)
            for origin, payload in zip(origins, compressed, strict=True):
                stored.id.write_direct_chunk(origin, payload)
