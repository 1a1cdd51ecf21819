"""Engine peaks to a labelled xarray.Dataset, and its atomic NetCDF archive.

The physics never writes files: the engine returns arrays, this module names them. Every
variable and coordinate carries CF-style `units` and `long_name`; global attributes hold the
provenance (versions, commit, every model setting and decision, each record's source).
Dimensions stay orthogonal (no stacked MultiIndex): record, the swept parameters, then floor
or story.
"""
from __future__ import annotations

import glob
import inspect
import json
import os
import re
import subprocess
import tempfile
from datetime import datetime, timezone
from pathlib import Path

import numpy as np
import xarray as xr

import engine

from .grid import BASELINE_COR, BASELINE_K, HERTZDAMP_EXPONENT, WALL_K_MEANING, Grid
from .run import _project_version, engine_fingerprint, record_hash

# name -> (units, long_name, trailing dimension or None)
PEAK_META = {
    "peak_total_accel": ("m s-2", "peak total (absolute) floor acceleration", "floor"),
    "peak_interstory_drift": ("m", "peak interstory deflection", "story"),
    "peak_isolator_disp": ("m", "peak isolator displacement", None),
    "max_indentation": ("m", "maximum indentation at the moat wall", None),
    "max_impact_force": ("N", "maximum impact force on the moat wall", None),
    "n_impacts": ("1", "number of impacts on the moat wall", None),
    "impact_energy": ("J", "energy dissipated by the moat-wall contacts", None),
}
BLOCK_LABEL = {
    "": "",
    "baseline_": " without bumpers (bare wall at the full gap: linear viscoelastic, "
                 f"k = {BASELINE_K:g} N/m, COR {BASELINE_COR})",
    "unconstrained_": " without moat wall (unconstrained)",
}
AMPLIFICATION = {
    "amplification_total_accel": ("peak_total_accel",
                                  "peak floor acceleration, bumpers / no bumpers (Fig. 14)"),
    "amplification_interstory_drift": ("peak_interstory_drift",
                                       "peak interstory deflection, bumpers / no bumpers "
                                       "(Fig. 15)"),
}
PARAM_META = {
    "gap": ("m", "clear gap between base slab and moat wall, before bumpers"),
    "thickness": ("m", "bumper thickness"),
    "strain": ("1", "ultimate compressive strain of the bumper rubber"),
    "n_bumpers": ("1", "number of bumpers on each side"),
    "cor": ("1", "coefficient of restitution of the impacts"),
}
COMPRESSION = {"zlib": True, "complevel": 4}


def build_dataset(grid: Grid, records, results: list[dict[str, np.ndarray]], dt: float,
                  building: engine.Building, names: list[str],
                  arguments: dict | None = None) -> xr.Dataset:
    """Label the per-record peak arrays of `run.run` (each (M, ...)) as a Dataset.

    records: the Record objects run, named `names` in the record coordinate.
    """
    coords = _coords(grid, records, names)
    data_vars = {}
    start = 0
    for block in grid.blocks:
        part = slice(start, start + block.size)
        start += block.size
        for name, (units, long_name, tail) in PEAK_META.items():
            values = np.stack([res[name][part] for res in results])
            values = values.reshape(len(records), *block.shape, *values.shape[2:])
            dims = ("record", *block.dims) + ((tail,) if tail else ())
            data_vars[block.prefix + name] = xr.Variable(
                dims, values, {"units": units, "long_name": long_name + BLOCK_LABEL[block.prefix]})
    ds = xr.Dataset(data_vars, coords=coords)
    if grid.block("baseline_") is not None:
        for name, (peak, long_name) in AMPLIFICATION.items():
            ratio = ds[peak] / ds["baseline_" + peak]
            ds[name] = ratio.transpose(*ds[peak].dims)
            ds[name].attrs = {"units": "1", "long_name": long_name}
    ds.attrs = provenance(grid, records, names, dt, building, arguments)
    return ds


def _coords(grid: Grid, records, names: list[str]) -> dict:
    coords = {
        "record": ("record", np.array(names, dtype=str),
                   {"units": "1", "long_name": "ground-motion record"}),
        "floor": ("floor", np.arange(5),
                  {"units": "1", "long_name": "level (0 = isolation level, 4 = roof)"}),
        "story": ("story", np.arange(1, 5),
                  {"units": "1", "long_name": "story (story i joins level i-1 to level i)"}),
        "record_source": ("record", np.array([str(r.source) for r in records], dtype=str),
                          {"units": "1", "long_name": "where the record was read from"}),
        "record_pga": ("record", np.array([np.max(np.abs(r.accel)) for r in records]),
                       {"units": "m s-2", "long_name": "peak ground acceleration"}),
        "record_dt": ("record", np.array([float(r.dt) for r in records]),
                      {"units": "s", "long_name": "record sampling step"}),
        "record_duration": ("record", np.array([len(r.accel) * float(r.dt) for r in records]),
                            {"units": "s", "long_name": "record length"}),
    }
    for name in (*grid.coords, *grid.fixed):
        units, long_name = _param_meta(grid, name)
        value = grid.coords[name] if name in grid.coords else grid.fixed[name]
        if name == "n_bumpers":
            value = np.asarray(value).astype(np.int64)
        dims = (name,) if name in grid.coords else ()
        coords[name] = (dims, np.asarray(value), {"units": units, "long_name": long_name})
    return coords


def _param_meta(grid: Grid, name: str) -> tuple[str, str]:
    if name == "wall_k":
        units, long_name = WALL_K_MEANING[grid.impact]
        return units.replace("N/m^1.5", "N m-1.5").replace("N/m", "N m-1"), long_name
    return PARAM_META[name]


def provenance(grid: Grid, records, names: list[str], dt: float, building: engine.Building,
               arguments: dict | None = None) -> dict:
    """Global attributes: versions, every model setting and decision, records, arguments."""
    law = grid.impact
    attrs = {
        "title": "bumpers: peak responses of a seismically isolated building pounding on its "
                 "moat wall",
        "Conventions": "CF-1.8",
        "project": "bumpers",
        "project_version": _project_version(),
        "git_commit": _git_commit(),
        "engine_fingerprint": engine_fingerprint(),
        "date_created": datetime.now(timezone.utc).isoformat(timespec="seconds"),
        "dt": dt,
        "dt_units": "s",
        "integrator": "explicit central differences (engine.simulate); ground motion "
                      "linearly interpolated onto dt",
        "impact_law": law,
        "swept_parameters": " ".join(grid.coords) or "none",
        "fixed_parameters": " ".join(grid.fixed) or "none",
        "m_eff": grid.m_eff,
        "m_eff_units": "kg",
        "m_eff_decision": "wall mass infinite, so m_eff = m1 m2 / (m1 + m2) -> base-slab mass",
        "cor_decision": "COR 0.45 for bumper impacts (the paper's rubber, section 3.4) unless "
                        "swept; COR 0.5 for bare-wall (no-bumper) impacts",
        "gap_decision": "gap is the clearance before bumpers; bumper runs use gap - thickness "
                        "(Fig. 14), the no-bumper baseline the full gap",
        "baseline": (f"linear viscoelastic wall (Eq. 1-3), k = {BASELINE_K:g} N/m, COR "
                     f"{BASELINE_COR}, at the full gap"
                     if grid.block("baseline_") is not None else "none"),
        "unconstrained": ("no moat wall (engine.Contact.none)"
                          if grid.block("unconstrained_") is not None else "none"),
        "impact_law_defaults": json.dumps(_law_defaults(law)),
    }
    if law == "hertzdamp":
        attrs["hertzdamp_exponent"] = HERTZDAMP_EXPONENT
    attrs.update(_building_attrs(building))
    for name, rec in zip(names, records, strict=True):
        name = re.sub(r"[^A-Za-z0-9_]", "_", name)  # a valid attribute name
        attrs[f"record_{name}_source"] = str(rec.source)
        note = getattr(rec, "note", "") or ""
        if note:
            attrs[f"record_{name}_note"] = note
        found_in = getattr(rec, "found_in", None)
        if found_in:
            attrs[f"record_{name}_found_in"] = found_in
            if found_in == "stand-in":
                attrs[f"record_{name}_substitution"] = note
    attrs["records"] = json.dumps([_record_meta(name, rec)
                                   for name, rec in zip(names, records, strict=True)])
    if arguments is not None:
        attrs["sweep_arguments"] = json.dumps(arguments, sort_keys=True)
    return attrs


def _law_defaults(law: str) -> dict:
    """The engine's own defaults of the contact constructor (material constants, rules)."""
    constructor = {"bumper": engine.Contact.bumper, "linear": engine.Contact.linear,
                   "jankowski": engine.Contact.jankowski,
                   "hertzdamp": engine.Contact.hertzdamp}.get(law)
    if constructor is None:
        return {}
    return {name: p.default for name, p in inspect.signature(constructor).parameters.items()
            if p.default is not inspect.Parameter.empty}


def _building_attrs(building: engine.Building) -> dict:
    attrs = {}
    for name, value in vars(building).items():
        attrs[f"building_{name}"] = _attr_value(value)
    attrs["building_units"] = ("masses kg, story_stiffness k1 k2 N/m, fy_ratio of the total "
                               "weight, g m s-2")
    attrs["building_yield_displacement"] = building.yield_displacement
    attrs["damping_decision"] = (
        "paper: isolation dashpot 2 zeta_iso sqrt(k1 M_tot), stiffness-proportional story "
        "dashpots 2 zeta_sup k / omega_1 (fixed-base)" if building.damping == "paper" else
        "modal: classical damping, zeta_iso in mode 1, zeta_sup in modes 2-5")
    return attrs


def _attr_value(value):
    """A NetCDF-storable attribute: numbers, number arrays and strings pass, the rest as text."""
    if isinstance(value, (bool, np.bool_)) or value is None:
        return str(value)
    if isinstance(value, (int, float, str, np.number)):
        return value
    array = np.asarray(value)
    return array if array.dtype.kind in "iuf" else str(value)


def _record_meta(name: str, rec) -> dict:
    meta = {"name": name, "record_name": str(rec.name), "dt": float(rec.dt),
            "npts": len(rec.accel), "pga": float(np.max(np.abs(rec.accel))),
            "sha256": record_hash(rec.accel, rec.dt)}
    for field in ("rsn", "event", "station", "component", "source", "found_in", "note"):
        value = getattr(rec, field, None)
        if value not in (None, ""):
            meta[field] = value if isinstance(value, (int, float)) else str(value)
    return meta


def _git_commit() -> str:
    """HEAD of the project's checkout (+ '-dirty' with local changes), or 'unknown'."""
    root = Path(__file__).resolve().parents[1]
    try:
        commit = subprocess.run(["git", "rev-parse", "HEAD"], cwd=root, capture_output=True,
                                text=True, timeout=10, check=True).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"],
                               cwd=root, capture_output=True, text=True, timeout=10,
                               check=True).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    return commit + ("-dirty" if dirty else "")


def write_netcdf(ds: xr.Dataset, path) -> Path:
    """Write `ds` to `path` (netCDF4, zlib) atomically: the file is complete or absent.

    The data goes to a temporary file in the same folder, then os.replace renames it, which is
    atomic on one filesystem; a failure or a kill leaves at most a hidden .tmp file.
    """
    path = Path(path)
    encoding = {name: COMPRESSION for name, var in ds.data_vars.items()
                if var.dtype.kind in "fiu"}
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    os.close(fd)
    try:
        ds.to_netcdf(tmp, engine="netcdf4", format="NETCDF4", encoding=encoding)
        with open(tmp, "rb") as f:
            os.fsync(f.fileno())  # the bytes are on disk before the name points at them
        os.chmod(tmp, 0o666 & ~_umask())  # mkstemp made it private; an archive is not
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    for stale in path.parent.glob(f".{glob.escape(path.name)}.*.tmp"):
        stale.unlink(missing_ok=True)  # left by writers that were killed before the rename
    return path


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask
