"""Time histories of a few wall configurations under one record, labelled like sweep peaks.

    from pipeline.histories import histories
    ds = histories("kobe", {"no_pounding": {"impact": "none"},
                            "no_bumpers": {"impact": "linear", "gap": 0.15},
                            "bumpers": {"impact": "bumper", "gap": 0.15, "thickness": 0.05}})

The practical example of the paper (section 4, Figs. 9-13) needs what a sweep does not keep:
the base acceleration against time and the force-indentation loops of the impacts. A
configuration is written in pipeline.sweep's vocabulary with one value per parameter: impact
("none" for no wall, "bumper", "linear", "jankowski", "hertzdamp"), gap, thickness, strain,
n_bumpers, wall_k, cor (SI units; pipeline.grid says how each maps onto each law, and omitted
ones take the law's default; the bare wall of the sweeps' baseline is impact="linear" with its
defaults, k 2.5e9 N/m, COR 0.5). pipeline.grid validates each configuration and builds the
engine Contact; all configurations of the record run in one engine batch, in this process.

The Dataset has dims configuration, time (and floor, story): the histories sampled every
`every` integration steps, and the peaks of every configuration under the same names and units
as a sweep's archive (engine.results). Peaks are taken over every step, so with
every > 1 a history's maximum may fall slightly under its peak; with every = 1 they are equal.
"""
from __future__ import annotations

import dataclasses
import json
import math
from collections.abc import Mapping

import numpy as np
import xarray as xr

import engine
from engine.impact import M_EFF
from engine.results import HISTORIES, HISTORY_NAMES, RESIDUALS

from .archive import (
    labelled_dataset,
    level_coords,
    parameter_meta,
    peak_variables,
    quantity_variable,
    record_coords,
    variable,
)
from .assess.sweep_variables import derived_variables
from .building_file import check_building
from .checks import check_count, resolve_records
from .errors import SweepError
from .grid import (
    NO_WALL,
    Block,
    Grid,
    check_dt,
    contact_for,
    describe_member,
    make_grid,
)
from .members import IMPACT_LAWS, PARAMS
from .progress import Progress
from .provenance import (
    arguments_attribute,
    common_attributes,
    decision_attributes,
    law_defaults,
    plain,
    record_attributes,
    run_attributes,
)

CONFIG_KEYS = ("impact", *PARAMS, "m_eff")
TITLE = ("bumpers: time histories and peak responses of a seismically isolated building "
         "pounding on its moat wall, per wall configuration")


def histories(record, configurations: Mapping[str, Mapping], dt: float | None = None,
              every: int = 4, records_dir=None, building=None, m_eff: float | None = None,
              duration: float | None = None, quiet: bool = True) -> xr.Dataset:
    """Simulate each configuration under one record; keep its time histories and peaks.

    record: a paper key, library name, AT2 path or Record (see pipeline.records.load_record);
    configurations: name -> {"impact": ..., "gap": m, ...} (module docstring); dt: integration
        step (s, default engine.DEFAULT_DT), refused at or above the stability limit;
    every: keep every `every`-th step of the histories (every * dt s apart);
    records_dir: folder of AT2 files for the record's lookup; building: engine.Building
        (default: the paper's); m_eff: effective impact mass (kg) unless a configuration sets
        its own;
    duration: simulate only the first `duration` s of the record (a quick look: peaks are then
        those of the segment, and the archive says so); quiet: no progress bar.

    Returns an xarray.Dataset, dims configuration, time, floor (0-4), story (1-4) for the
    paper's building: isolator_disp (m), total_accel (m/s^2; floor), impact_force (N),
    indentation (m) and isolator_force (N) against time (engine.results.HISTORIES), the peaks
    (engine.results.PEAKS: peak_total_accel (m/s^2; floor), peak_interstory_drift (m; story),
    peak_isolator_disp (m), max_indentation (m), max_impact_force (N), n_impacts, impact_energy
    (J), peak_isolator_force (N), peak_story_shear (N; story), peak_floor_velocity (m/s; floor))
    and the residuals (engine.results.RESIDUALS); per-configuration coordinates impact, the
    parameters (NaN where a law does not use one), clear_gap and crush_indentation (the engine's
    clear_gap and delta_u, m); scalar coordinates of the record; provenance attributes
    (pipeline.provenance: common, the run, the decisions, the record, and the histories' own).
    Raises SweepError, naming the parameter, before any simulation runs.
    """
    m_eff = M_EFF.default if m_eff is None else m_eff
    names, grid = configuration_grid(configurations, m_eff)
    building = check_building(building)
    dt = check_dt(grid, engine.DEFAULT_DT if dt is None else dt, building)
    every = check_count("every", every, minimum=1)
    recs, rec_names = resolve_records(record, records_dir)
    if len(recs) != 1:
        raise SweepError(f"records: histories runs one record at a time, got {len(recs)}")
    rec, rec_name = recs[0], rec_names[0]
    if duration is not None:
        rec = segment(rec, duration)

    contact = contact_for(grid.members)
    size = len(names)
    progress = Progress(size, quiet=quiet)
    result = engine.simulate(rec.accel, rec.dt, contact, building=building, dt=dt,
                             history=engine.History(members=list(range(size)), every=every),
                             progress=lambda step, steps: progress.running(0, size * step / steps))
    progress.advance(size, 0)
    progress.close()

    arguments = plain({"record": rec_name, "configurations": _given(configurations), "dt": dt,
                       "every": every, "m_eff": m_eff, "duration": duration})
    return _dataset(names, grid, contact, rec, rec_name, result, dt, every, building,
                    m_eff, duration, arguments)


def concat_records(parts, t_end: float | None = None) -> xr.Dataset:
    """Stack the Datasets of `histories` for several records along a new record dimension.

    The histories share one time axis, from 0 to the end of the longest record, or to t_end
    (s) when given: histories are cut there (the peaks stay those of the whole simulation). A
    record that ends before the axis does is NaN after its end, and the history variables'
    attrs say so; history_end (record) holds each record's last time. Every part must have the
    same configurations, step and output interval. Provenance attributes of every record are
    kept; those that differ between records are gathered per record.
    """
    parts = list(parts)
    if not parts:
        raise SweepError("concat_records: no Dataset given")
    first = parts[0]
    for ds in parts[1:]:
        if list(ds.configuration.values) != list(first.configuration.values):
            raise SweepError(f"concat_records: configurations differ: "
                             f"{list(first.configuration.values)} vs "
                             f"{list(ds.configuration.values)}")
        for key in ("dt", "history_interval"):
            if ds.attrs.get(key) != first.attrs.get(key):
                raise SweepError(f"concat_records: {key} differs between records "
                                 f"({first.attrs.get(key)} vs {ds.attrs.get(key)})")
    if t_end is not None:
        t_end = float(t_end)
        if not t_end > 0:
            raise SweepError(f"t_end must be positive (s), got {t_end}")
        tolerance = 1e-6 * first.attrs["history_interval"]
        parts = [ds.isel(time=ds.time.values <= t_end + tolerance) for ds in parts]
    names = [str(ds.record.values) for ds in parts]
    ends = [float(ds.time.values[-1]) for ds in parts]
    combined = xr.concat(parts, dim="record", join="outer", data_vars="all",
                         coords="different", compat="equals", combine_attrs="drop_conflicts")
    combined.coords["history_end"] = ("record", np.array(ends),
                                      {"units": "s", "long_name": "last time of the record's "
                                       "histories (NaN after it)"})
    axis_end = float(combined.time.values[-1])
    short = [f"{name} ends at {end:g} s" for name, end in zip(names, ends, strict=True)
             if end < axis_end]
    for name in HISTORY_NAMES:
        if short:
            combined[name].attrs["fill"] = ("NaN after the end of a record shorter than the "
                                            f"common time axis ({'; '.join(short)})")
    combined.time.attrs["long_name"] = "time from the start of the record"
    if t_end is not None:
        combined.time.attrs["cut"] = (f"histories kept up to {t_end:g} s; peaks are over the "
                                      "whole simulation")
    # Attributes that differ between records (configurations, arguments, ...): per record.
    for key in dict.fromkeys(k for ds in parts for k in ds.attrs):
        if key in combined.attrs:
            continue
        values = [_decoded(ds.attrs.get(key)) for ds in parts]
        if key == "date_created":
            combined.attrs[key] = max(map(str, values))
        elif key == "records":
            combined.attrs[key] = json.dumps([item for value in values for item in value])
        else:
            combined.attrs[key] = json.dumps(dict(zip(names, plain(values), strict=True)))
    return combined


def _decoded(value):
    """An attribute value, JSON text decoded."""
    if isinstance(value, str) and value[:1] in "[{":
        try:
            return json.loads(value)
        except ValueError:
            return value
    return value


def segment(record, duration: float):
    """The first `duration` s of a record (samples t = 0 .. duration), noted in its source and
    note so that the archive tells it apart from the whole record."""
    try:
        duration = float(duration)
    except (TypeError, ValueError):
        raise SweepError(f"duration must be a number (s), got {duration!r}") from None
    if not (duration > 0 and math.isfinite(duration)):
        raise SweepError(f"duration must be positive (s), got {duration}")
    if not dataclasses.is_dataclass(record):
        raise SweepError("duration: only a pipeline.records.Record can be cut to a segment")
    n = min(int(math.floor(duration / record.dt + 1e-9)) + 1, len(record.accel))
    if n < 2:
        raise SweepError(f"duration {duration:g} s is shorter than two samples of "
                         f"{record.name} (dt {record.dt:g} s)")
    if n == len(record.accel):
        return record
    what = f"first {(n - 1) * record.dt:g} s of {record.duration:g} s"
    note = getattr(record, "note", "") or ""
    return dataclasses.replace(record, accel=record.accel[:n],
                               source=f"{record.source} ({what})",
                               note=(note + " " if note else "") + f"Segment: {what} only.")


def configuration_grid(configurations, m_eff) -> tuple[list[str], Grid]:
    """Validate the named configurations (each by pipeline.grid's rules, as a single-member
    grid); their names and the members as one Grid, as a sweep's and a listed table's are
    (one block along `configuration`, in the order given; its impact names every law it runs,
    space-separated, as they first appear)."""
    if not isinstance(configurations, Mapping) or not configurations:
        raise SweepError("configurations must be a non-empty dict: name -> parameters")
    names, grids = [], []
    for name, config in configurations.items():
        if not isinstance(name, str) or not name.strip():
            raise SweepError(f"configurations: a name must be a non-empty string, got {name!r}")
        if not isinstance(config, Mapping):
            raise SweepError(f"configurations[{name!r}] must be a dict of parameters, "
                             f"got {config!r}")
        unknown = sorted(set(config) - set(CONFIG_KEYS))
        if unknown:
            raise SweepError(f"configurations[{name!r}]: unknown parameter(s) {unknown}; "
                             f"use {', '.join(CONFIG_KEYS)}")
        impact = config.get("impact", "bumper")
        params = {p: config[p] for p in PARAMS if config.get(p) is not None}
        for p, value in params.items():
            if np.ndim(value) != 0:
                raise SweepError(f"configurations[{name!r}]: {p} takes one value per "
                                 f"configuration, got {value!r}")
        member_m_eff = config.get("m_eff", m_eff)
        try:
            if impact == NO_WALL:
                if params:
                    raise SweepError(f"{', '.join(params)} need a wall, not impact='none'")
                grid = make_grid(None, unconstrained=True, m_eff=member_m_eff)
            elif impact in IMPACT_LAWS:
                grid = make_grid(params.pop("gap", None), impact=impact, m_eff=member_m_eff,
                                 **params)
            else:
                raise SweepError(f"impact: unknown impact law {impact!r}; choose one of "
                                 f"{(NO_WALL, *IMPACT_LAWS)}")
        except SweepError as err:
            raise SweepError(f"configurations[{name!r}]: {err}") from None
        names.append(name)
        grids.append(grid)
    members = np.concatenate([grid.members for grid in grids])
    laws = " ".join(dict.fromkeys(grid.impact for grid in grids))
    block = Block("", ("configuration",), (members.size,), members)
    return names, Grid(laws, {}, {}, (block,), float(m_eff))


def _given(configurations) -> dict:
    return {name: dict(config) for name, config in configurations.items()}


def _dataset(names, grid, contact, rec, rec_name, result, dt, every, building,
             m_eff, duration, arguments) -> xr.Dataset:
    hist = result.history
    config = "configuration"
    data_vars = {q.name: quantity_variable(q, (config, "time"), hist[q.name])
                 for q in HISTORIES}
    data_vars.update(peak_variables(result.peaks(), (config,)))
    data_vars.update(peak_variables(result.residuals(), (config,), quantities=RESIDUALS))

    members = grid.members
    laws = [str(law) for law in members["law"]]  # each configuration's
    # One record: its coordinates are scalars (xr.concat over records stacks them).
    coords = {key: var[0] for key, var in record_coords([rec], [rec_name]).items()}
    coords.update(level_coords(building.n_levels))
    coords["configuration"] = variable(config, np.array(names, dtype=str), "1",
                                       "moat-wall configuration")
    coords["time"] = variable("time", hist["time"], "s", "time from the start of the record",
                              sampling=f"every {every} integration step(s) of {dt:g} s")
    coords["impact"] = variable(config, np.array(laws, dtype=str), "1",
                                "impact law ('none': no moat wall)")
    for p in PARAMS:
        units, long_name = parameter_meta(laws, p)
        coords[p] = variable(config, members[p], units,
                             long_name + " (NaN: not used by the configuration's law)")
    coords["m_eff"] = variable(config, members["m_eff"], "kg", "effective impact mass")
    coords["clear_gap"] = variable(config, _finite(contact.clear_gap), "m",
                                   "clear gap to the contact surface (gap - (thickness - "
                                   "cavity) with bumpers; NaN: no wall)")
    coords["crush_indentation"] = variable(config, _finite(contact.delta_u), "m",
                                           "indentation at which the bumpers are crushed, "
                                           "min(strain x thickness, thickness - cavity) (NaN: "
                                           "no crush limit)")

    attrs = {
        **common_attributes(TITLE), **run_attributes(dt, building),
        **decision_attributes(m_eff), **record_attributes([rec], [rec_name]),
        "impact_law": "per configuration (see the impact coordinate and `configurations`)",
        "swept_parameters": "configuration",
        "fixed_parameters": "none",
        "baseline": "none (a bare wall is a configuration with impact='linear')",
        "unconstrained": "none (no wall is a configuration with impact='none')",
        "impact_law_defaults": json.dumps({law: law_defaults(law)
                                           for law in dict.fromkeys(laws) if law != NO_WALL}),
        "configurations": json.dumps({name: describe_member(member)
                                      for name, member in zip(names, members, strict=True)}),
        "history_every": every,
        "history_interval": every * dt,
        "history_interval_units": "s",
        "history_note": (f"histories keep one integration step in {every} ({every * dt:g} s "
                         "apart); peaks are taken over every step, so a history's maximum can "
                         "fall slightly under its peak"),
        "record_segment": ("whole record" if duration is None
                           else f"first {float(duration):g} s only (peaks of the segment)"),
        **arguments_attribute("histories", arguments),
    }
    ds = labelled_dataset(data_vars, coords, attrs)
    return ds.assign({name: value for name, (value, _) in
                      derived_variables(ds, building).items()})


def _finite(values) -> np.ndarray:
    values = np.asarray(values, dtype=float)
    return np.where(np.isfinite(values), values, np.nan)
