"""Labelled xarray Datasets and their atomic NetCDF archives.

The physics never writes files: the engine returns arrays, this module names them. Every
Dataset the project writes (sweeps, histories, the two-body recipes) is built by
`labelled_dataset`, which refuses a variable or coordinate without `units` and `long_name`.
Dimensions stay orthogonal (no stacked MultiIndex): record, the swept parameters, then floor
or story, sized by the building that ran. The engine's results are labelled with their
declarations (engine.results: units, long names, trailing axis); global attributes
(provenance) come from provenance.py.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

import engine
from engine.impact import LAWS
from engine.isolators import LAWS as ISOLATOR_LAWS
from engine.results import (
    COLLAPSE,
    COLLAPSE_MODES,
    DIRECTIONS,
    PEAKS,
    WALLS,
    Quantity,
    level_axes,
)

from . import parallel_deflate
from .grid import Grid, baseline_text, swept_parameter
from .members import EXCITATION_PARAMETERS, ISOLATOR_PARAMS, LISTED_PARAMS
from .provenance import (
    ARCHIVE_VERSION,
    ARCHIVE_VERSION_ATTRIBUTE,
    attributes,
    plan_attributes,
    record_labels,
    source_text,
    storable,
)
from .writing import Staged

COMPRESSION = {"zlib": True, "complevel": 4}


def is_numeric(values) -> bool:
    """Whether an array's values are numbers (or booleans): what a `units` attribute is for."""
    return np.dtype(values.dtype).kind in "biufc"


def variable(dims, values, units: str, long_name: str, **attrs) -> xr.Variable:
    """A labelled variable: dims (tuple or one name), values, CF units and long_name. Text
    (string) values take no units: `units` is dropped for them (CF: units are for numbers)."""
    dims = (dims,) if isinstance(dims, str) else tuple(dims)
    values = values if hasattr(values, "chunks") else np.asarray(values)  # dask stays lazy
    own = {"units": units} if is_numeric(values) else {}
    return xr.Variable(dims, values, {**own, "long_name": long_name, **attrs})


def labelled_dataset(data_vars: dict, coords: dict, attrs: dict | None = None) -> xr.Dataset:
    """The Dataset of every archive: data variables and coordinates given as xr.Variable (see
    `variable`) or (dims, values, attrs) tuples; each must carry `long_name`, and `units` when
    its values are numbers (text takes none: a `units` given to it is dropped). Attributes
    are made storable (provenance.storable: None left out, booleans 0/1) and the archive's
    schema version (provenance.ARCHIVE_VERSION) is stamped here, once for every archive."""
    ds = xr.Dataset(data_vars, coords=coords,
                    attrs={**storable(attrs or {}), ARCHIVE_VERSION_ATTRIBUTE: ARCHIVE_VERSION})
    for name, var in ds.variables.items():
        if not is_numeric(var):
            var.attrs.pop("units", None)
        var.attrs = storable(var.attrs)
        needed = ("units", "long_name") if is_numeric(var) else ("long_name",)
        missing = [key for key in needed if key not in var.attrs]
        if missing:
            raise ValueError(f"archive variable {name!r} lacks {' and '.join(missing)}")
    return ds


def quantity_variable(q: Quantity, lead_dims: tuple[str, ...], values,
                      long_name: str | None = None) -> xr.Variable:
    """One of the engine's results (engine.results), its values shaped lead_dims + the
    quantity's own trailing axes (floor, story or wall; then direction for a per-direction
    quantity of a run in plan), labelled with its declaration."""
    dims = tuple(lead_dims) + ((q.along,) if q.along else ()) \
        + (("direction",) if q.direction else ())
    labelled = variable(dims, values, q.units, q.long_name if long_name is None else long_name)
    if q.flags:  # a code: its values' meanings, as CF flags
        labelled.attrs["flag_values"] = np.arange(len(q.flags), dtype=q.dtype)
        labelled.attrs["flag_meanings"] = " ".join(q.flags)
    return labelled


COLLAPSE_MODE = {q.name: q for q in COLLAPSE}["collapse_mode"]
"""The declaration of how a run ended (engine.results.COLLAPSE): its units, long name, int8
codes and their CF flags."""


def collapse_mode_variable(dims, values, long_name: str | None = None) -> xr.Variable:
    """How each run ended, as the sweeps' archives label it (`quantity_variable` of the
    engine's collapse_mode: int8 codes, units "1", CF flag_values and flag_meanings): values
    (...) the runs' codes (engine.results.COLLAPSE_MODES, 0 where a run did not collapse) over
    dims (a study's runs, as its `collapsed`); long_name: the declaration's, else this."""
    return quantity_variable(COLLAPSE_MODE, tuple(dims), np.asarray(values).astype(np.int8),
                             long_name)


def collapse_mode_coords() -> dict:
    """The coordinate `mode` of a count of collapses by mode: the modes a collapse can have
    (engine.results.COLLAPSE_MODES less "none", in the order of their codes 1, 2, ...)."""
    return {"mode": variable("mode", np.array(COLLAPSE_MODES[1:]), "1",
                             "how the runs collapsed (engine.results.COLLAPSE_MODES): "
                             "collapse_mode's codes 1 to " + str(len(COLLAPSE_MODES) - 1))}


def block_long_name(q: Quantity, prefix: str) -> str:
    """The long name of peak `q` in the block of members `prefix` (pipeline.grid)."""
    if prefix == "baseline_":
        return (f"{q.long_name} without bumpers (bare wall at the full gap: linear "
                f"viscoelastic, {baseline_text()})")
    if prefix == "unconstrained_":
        return (f"{q.long_name} (zero: the unconstrained run has no moat wall)" if q.wall
                else f"{q.long_name} without moat wall (unconstrained)")
    return q.long_name


def peak_variables(peaks: dict, lead_dims: tuple[str, ...],
                   prefix: str = "", quantities=PEAKS) -> dict[str, xr.Variable]:
    """The engine's peaks (name -> array shaped lead_dims + the peak's own trailing axes),
    labelled with their declarations (engine.results.PEAKS, and PLAN_PEAKS in plan) as the
    block `prefix`'s."""
    return {prefix + q.name: quantity_variable(q, lead_dims, peaks[q.name],
                                               block_long_name(q, prefix))
            for q in quantities}


def plan_coords(moat: str) -> dict:
    """The direction and wall coordinates of a run in plan."""
    return {
        "direction": variable("direction", np.array(DIRECTIONS), "1",
                              "horizontal direction: x, the pair's first component, and y, "
                              "its second, 90 degrees counterclockwise from x"),
        "wall": variable("wall", np.array(WALLS[moat]), "1",
                         "wall of the moat, named by its outward normal (+x: the wall the slab "
                         "hits moving towards +x)" if moat == "rectangular" else
                         "the circular moat's one wall"),
    }


def point_coords(building: engine.Building, bumper_positions) -> dict:
    """The contact points of a building that twists: their wall and position along it."""
    from engine.torsion import contact_points

    points = contact_points(np.array([building.torsion.plan_size]), bumper_positions)
    return {
        "point": variable("point", np.arange(points.wall.size), "1",
                          "contact point of the moat: a corner of the slab against a bare "
                          "wall, or a bumper (engine.torsion.contact_points)"),
        "point_wall": variable("point", np.array(WALLS["rectangular"])[points.wall], "1",
                               "the contact point's wall, named by its outward normal"),
        "point_along": variable("point", points.along[0], "m",
                                "the contact point's position along its wall from the plan's "
                                "centre (y for the x walls, x for the y walls)"),
    }


def level_coords(n_levels: int) -> dict:
    """The floor and story coordinates of a building of n_levels levels."""
    return {axis: variable(axis, values, units, long_name)
            for axis, (values, units, long_name) in level_axes(n_levels).items()}


def record_coords(records, names: list[str]) -> dict:
    """Coordinates along `record`: labels (names, see provenance.record_labels), the records'
    own names, sources, PGA as run and unscaled (m/s^2), scale factor, sampling step and
    length (s)."""
    return {
        "record": variable("record", np.array(names, dtype=str), "1",
                           "ground-motion record, as named in the call (a paper record by its "
                           "key, a library record by its RSN<n>:<component> selector or its "
                           "name)"),
        "record_name": variable("record", np.array([str(r.name) for r in records], dtype=str),
                                "1", "the record's own name"),
        "record_source": variable("record", np.array([source_text(r) for r in records],
                                                     dtype=str),
                                  "1", "where the record was read from (a file: its absolute "
                                  "path; else the library or built-in data it came from)"),
        "record_pga": variable("record", [np.max(np.abs(r.accel)) for r in records], "m s-2",
                               "peak ground acceleration (of the record as run)"),
        "record_scale": variable("record", [float(getattr(r, "scale", 1.0)) for r in records],
                                 "1", "factor the original record was multiplied by"),
        "record_unscaled_pga": variable(
            "record", [getattr(r, "unscaled_pga", None) or np.max(np.abs(r.accel))
                       for r in records], "m s-2", "peak ground acceleration before scaling"),
        "record_dt": variable("record", [float(r.dt) for r in records], "s",
                              "record sampling step"),
        "record_duration": variable("record", [len(r.accel) * float(r.dt) for r in records],
                                    "s", "record length"),
        "record_found_in": variable("record", np.array(
            [getattr(r, "found_in", None) or "given" for r in records], dtype=str), "1",
            "where the record came from: records_dir, built-in or library for a paper record "
            "found, stand-in for a substitute (see the record's note), given for a record "
            "named or passed directly"),
    }


def parameter_meta(laws, name: str) -> tuple[str, str]:
    """(units, long_name) of sweep parameter `name`, from the declarations of `laws` (one law
    name or several: a histories archive mixes laws; each law's meaning is then named)."""
    laws = [laws] if isinstance(laws, str) else list(dict.fromkeys(laws))
    using = [law for law in laws if law in LAWS and name in LAWS[law].PARAMETERS.swept()]
    texts = {}
    for law in using:
        param = swept_parameter(law, name)
        texts[law] = param.meaning + (f" ({param.equation})" if param.equation else "")
    units = {swept_parameter(law, name).units for law in using}
    if not using:  # no configuration uses it: the unit of any law that does
        law = next(law for law in LAWS if name in LAWS[law].PARAMETERS.swept())
        return swept_parameter(law, name).units, f"{name} (not used)"
    if len(set(texts.values())) == 1:
        long_name = next(iter(texts.values()))
    else:
        long_name = f"{name}: " + "; ".join(f"{law}: {text}" for law, text in texts.items())
    unit = units.pop() if len(units) == 1 else " or ".join(
        f"{swept_parameter(law, name).units} ({law})" for law in using)
    return unit, long_name


def parameter_coords(grid: Grid) -> dict:
    """The swept parameters as dimension coordinates, the fixed ones as scalar coordinates
    (the wall's, then the isolator's that replace the building's)."""
    coords = {}
    for name in (*grid.coords, *grid.fixed):
        if name in ISOLATOR_PARAMS:  # replaces the building's own value (building_isolator_*)
            param = ISOLATOR_LAWS[grid.isolator].PARAMETERS.swept()[name]
            units, long_name = param.units, f"{param.meaning} ({param.equation})"
        elif name in EXCITATION_PARAMETERS:
            param = EXCITATION_PARAMETERS[name]
            units, long_name = param.units, param.meaning
        else:
            units, long_name = parameter_meta(grid.impact, name)
        value = grid.coords[name] if name in grid.coords else grid.fixed[name]
        if name == "n_bumpers":
            value = np.asarray(value).astype(np.int64)
        coords[name] = variable((name,) if name in grid.coords else (), value, units, long_name)
    return coords


def listed_coords(grid: Grid) -> dict:
    """The columns of a grid of listed members (pipeline.listed) as coordinates along member
    (or record and member), labelled with their declarations."""
    if grid.listed is None:
        return {}
    coords = {"member": variable("member", np.arange(np.shape(grid.listed["law"])[-1]), "1",
                                 "the member's row in the listed table")}
    for name, values in grid.listed.items():
        dims = ("record", "member") if np.ndim(values) == 2 else ("member",)
        if name == "law":
            coords["law"] = variable(dims, np.asarray(values, dtype=str), "1",
                                     "the member's wall law (none: no wall)")
            continue
        if name in EXCITATION_PARAMETERS:
            param = EXCITATION_PARAMETERS[name]
            units, long_name = param.units, param.meaning
        elif name == "m_eff":
            units, long_name = "kg", "effective impact mass"
        elif name in LISTED_PARAMS:
            param = next(LAWS[law].PARAMETERS.numeric[name] for law in LAWS
                         if name in LAWS[law].PARAMETERS.numeric
                         and law in grid.impact.split())
            units, long_name = param.units, param.meaning
        else:
            units, long_name = parameter_meta(grid.impact.split(), name)
        unset = "the law's default" if name in LISTED_PARAMS else \
            "not a parameter of the member's law"
        coords[name] = variable(dims, np.asarray(values, dtype=float), units,
                                f"{long_name} (NaN: {unset})")
    return coords


def build_dataset(grid: Grid, run, results: list[dict[str, np.ndarray]] | None,
                  chunks=None, derive=None) -> xr.Dataset:
    """Label the per-record peak arrays of a sweep (each (M, ...), the grid's member order)
    as its Dataset.

    run: what the members ran under (pipeline.execute.run.Run: the records, named in the
    record coordinate, their factors, dt, the building, the moat). results=None builds a
    template instead (pipeline.execute.zarr_store): every peak a lazy dask array of fill
    values (NaN, -1 for counts), chunks(block) giving the chunk sizes over its swept dims, and
    no amplification ratios. A run in plan (records are then pipeline.records.RecordPair):
    PLAN_PEAKS too, with direction and wall coordinates. Records with intensity factors: the
    coordinate record_factor. derive: what a result means, computed from the labelled peaks
    (derive(ds, building, grid) -> name -> (DataArray, the peak it follows); the sweep passes
    pipeline.assess.sweep_variables.derived_variables), added as variables; None: peaks only.
    """
    records, building, moat, model = run.records, run.building, run.moat, run.model
    names = record_labels(records, run.names)
    n_points = run.n_points
    quantities = model.quantities(building.can_collapse)
    data_vars = {}
    start = 0
    for block in grid.blocks:
        part = slice(start, start + block.size)
        start += block.size
        peaks = {}
        for q in quantities:
            if results is None:
                import dask.array as da

                tail = q.trailing_shape(building.n_levels,
                                        len(WALLS[moat]) if model.in_plan else 1,
                                        n_points or 1)
                kind = np.dtype(q.dtype).kind
                fill = np.nan if kind == "f" else False if kind == "b" else -1
                peaks[q.name] = da.full((len(records), *block.shape, *tail), fill,
                                        dtype=q.dtype, chunks=(1, *chunks(block), *tail))
                continue
            # one record: a view of its peaks (a million members' stacked copy took 0.5 s)
            values = results[0][q.name][part][np.newaxis] if len(results) == 1 else \
                np.stack([res[q.name][part] for res in results])
            peaks[q.name] = values.reshape(len(records), *block.shape, *values.shape[2:])
        data_vars.update(peak_variables(peaks, ("record", *block.dims), block.prefix,
                                        quantities))
    coords = {**record_coords(records, names), **level_coords(building.n_levels),
              **parameter_coords(grid), **listed_coords(grid),
              **(plan_coords(moat) if model.in_plan else {}),
              **({} if n_points is None else point_coords(building, run.bumper_positions))}
    if run.factors is not None:
        coords["record_factor"] = variable(
            "record", np.asarray(run.factors, dtype=float), "1", "the record's intensity "
            "factor: a member's ground acceleration is the record's times this times its level")
    attrs = attributes(grid, records, names, run.dt, building, run.arguments)
    if model.in_plan:
        attrs.update(plan_attributes(moat))
    ds = labelled_dataset(data_vars, coords, attrs)
    if results is not None and derive is not None:
        ds = ds.assign({name: value for name, (value, _) in
                        derive(ds, building, grid).items()})
    return ds


def write_netcdf(ds: xr.Dataset, path) -> Path:
    """Write `ds` to `path` (netCDF4, zlib) atomically: the file is complete or absent.

    The data goes to a hidden temporary file in the same folder, then os.replace renames it,
    which is atomic on one filesystem; a failure or a kill leaves at most that temporary file,
    which the next write there sweeps away (pipeline.writing.Staged).
    """
    path = Path(path)
    with Staged() as stage:
        to_netcdf(ds, stage.path(path))
        stage.commit()
    return path


def to_netcdf(ds: xr.Dataset, path) -> None:
    """Write `ds` to `path` as netCDF4 with zlib (and HDF5's shuffle) on every numeric
    variable, the large ones compressed on every core (pipeline.parallel_deflate); not atomic:
    see write_netcdf."""
    encoding = {name: COMPRESSION for name, var in ds.data_vars.items()
                if var.dtype.kind in "fiu"}
    if parallel_deflate.parallel_variables(ds):
        try:
            parallel_deflate.write(ds, path, encoding)
            return
        except (ImportError, OSError, ValueError):
            pass  # h5py missing or unable to write this file: netCDF4 writes it all, slower
    ds.to_netcdf(path, engine="netcdf4", format="NETCDF4", encoding=encoding)
