"""The sweep's orchestration: the call checked, its grid of members built (pipeline.grid, or
a listed table: pipeline.listed), run by the executor into a store (pipeline.execute), what
the peaks mean computed (pipeline.assess.sweep_variables) and labelled into the archive
(pipeline.archive). `pipeline.sweep`, `pipeline.unconstrained_peaks` and
`pipeline.scale_to_displacement` are this module's, re-exported by the package (which loads
this module on first use only)."""
from __future__ import annotations

import dataclasses
import inspect
import os
import shutil
import warnings
from dataclasses import dataclass

import numpy as np

import engine

from .assess.sweep_variables import derived_variables
from .building_file import check_building
from .checks import check_count, resolve_pairs, resolve_records
from .errors import PlausibilityWarning, SweepError
from .execute.batches import default_batch_size
from .execute.executor import execute
from .execute.netcdf_store import NetCDFStore
from .execute.run import Run, run_model
from .execute.zarr_store import ZarrStore
from .grid import check_dt, make_grid, sweep_parameters
from .listed import check_records, listed_grid
from .members import DIMENSIONS, TORSION_PARAMS
from .motions.scaling import DEFAULT_DISPLACEMENT, DEFAULT_LIMITS
from .motions.scaling import scale_to_displacement as scale
from .provenance import plain
from .writing import check_out, guard


@dataclass(frozen=True)
class Conditions:
    """What every member runs under, as the call gives it (checked by `execute_sweep`):
    records (names, paths, Record objects or pairs) and the folder to look them up in, the
    step dt (s; None: engine.DEFAULT_DT), the building (None: the paper's), the moat (None:
    planar), the records' intensity factors (None or (R,) -), the bumpers' positions along
    the walls of a building that twists (m; None: its corners)."""

    records: object
    records_dir: object = None
    dt: float | None = None
    building: object = None
    moat: str | None = None
    factors: object = None
    bumper_positions: object = None


@dataclass(frozen=True)
class Compute:
    """Where and how the members run: workers (0 or 1: this process; >= 2 local dask
    workers), a dask scheduler (address or Client; None: none), the members per engine call
    (None: pipeline.execute.batches.default_batch_size), quiet (no progress line), the
    engine's time loop (engine.simulate's backend; None: its default)."""

    workers: int = 1
    scheduler: object = None
    batch_size: int | None = None
    quiet: bool = False
    backend: str | None = None


@dataclass(frozen=True)
class Output:
    """Where the results go: out (NetCDF path, or .zarr store; None: returned only), the work
    folder keeping finished batches (None: `<out>.work`), force (replace an archive of another
    sweep)."""

    out: object = None
    work_dir: object = None
    force: bool = False


@dataclass(frozen=True)
class SweepOptions:
    """The sweep's own options: every keyword of `sweep` besides the swept parameters, with
    its default, declared once (`sweep` documents each; its signature, for help() and IDEs,
    is made from these fields and the swept parameters: completed_sweep)."""

    impact: str = "bumper"
    dt: float | None = None
    workers: int = 1
    scheduler: object = None
    out: object = None
    baseline: bool = False
    unconstrained: bool = False
    building: object = None
    m_eff: float | None = None
    batch_size: int | None = None
    records_dir: object = None
    quiet: bool = False
    work_dir: object = None
    force: bool = False
    moat: str | None = None
    factors: object = None
    members: object = None
    bumper_positions: object = None
    backend: str | None = None


OPTIONS = tuple(f.name for f in dataclasses.fields(SweepOptions))
"""The names of the sweep's own options (SweepOptions), apart from the swept parameters."""


def sweep(records, **keywords):
    """Simulate every combination of the parameters under every record; label the peaks.

    records: paper keys ("kobe", "sylmar_converter", "olive_view", "pacoima"), library names,
        AT2 paths (see pipeline.records.load_record) or Record objects; one or a list.
    Every parameter after `records` is given by keyword.
    gap (m, the seismic gap before any bumper), thickness (m), cavity (m, depth of the wall
        cavity holding each bumper, paper 5.3), strain (-), n_bumpers (-), wall_k (N/m;
        N/m^1.5 for jankowski and hertzdamp), cor (-): the sweep parameters, those the impact
        laws declare (pipeline.members.PARAMS; another name raises SweepError). A scalar is held
        fixed (scalar coordinate), a sequence is swept (a dimension). None takes the impact
        law's declared default (engine.impact.LAWS[impact].PARAMETERS, where each law states
        what wall_k means for it); thickness, cavity, strain, n_bumpers apply to bumpers only.
    k1, k2 (N/m), fy_ratio (-) for a bilinear isolator; radius (m), mu_slow, mu_fast (-), rate
        (s/m), yield_disp (m) for a friction pendulum; L1, L2, L3, d1, d2, d3 (m), mu1, mu2,
        mu3 (-), yield_disp (m) for a triple friction pendulum: the building's isolator parameters
        (pipeline.members.ISOLATOR_PARAMS, declared in engine/isolators/laws/), which replace the
        building's own, held fixed or swept the same way (None: the building's). The
        baseline and unconstrained runs are then made once per isolator too.
    impact: "bumper" (the paper's rubber bumpers, default), "linear", "jankowski", "hertzdamp".
    dt: integration step (s), default engine.DEFAULT_DT; refused at or above the stability
        limit (engine.stable_dt).
    workers: 0 or 1 (default) runs in this process, the compiled kernel spreading each batch's
        members over every core with threads (measured the fastest on one machine: no worker
        start-up, no copies); >= 2 starts that many local dask worker processes, one thread
        each. Scripts need no `if __name__ == "__main__":` guard for them: the main script is
        hidden while the workers start, so they do not run it again.
    scheduler: a dask.distributed scheduler address (or Client) to run on instead.
    out: NetCDF path, written atomically; finished batches are kept in `<out>.work/` so that a
        rerun after a crash computes only what is missing; the folder goes once out is written.
        A path ending in `.zarr` writes a Zarr store instead, for sweeps too large for one
        file or the client's memory: workers write their batches into it directly, it is its
        own resume record, and the return value is the store opened lazily (see
        pipeline.execute.zarr_store).
    baseline: also run the bare wall without bumpers (the linear law at its defaults, k 2.5e9
        N/m, COR 0.5) once per (record, gap) at the full gap; adds baseline_* and
        amplification_* variables.
    unconstrained: also run each record without wall; adds unconstrained_* variables.
    building: engine.Building (default: the paper's); m_eff: effective impact mass (kg;
        default: the declared one, 320 t, the base slab).
    batch_size: members per engine call (default: pipeline.execute.batches.default_batch_size).
    records_dir: folder of AT2 files for the records' lookup; quiet: no progress bar.
    work_dir: a folder that keeps finished batches (default: `<out>.work` when out is given,
        removed once out is written; an explicit one is kept, and may be shared by several
        sweeps). Ctrl-C raises pipeline.errors.Interrupted (a KeyboardInterrupt) saying how
        many simulations are kept there; the same call again computes only the rest.
    moat: None (default) for the paper's planar model, one record component each; or
        "rectangular" / "circular" for runs in plan: records are then record PAIRS (anything
        pipeline.records.load_pair takes: "RSN953", a paper key, "A.AT2+B.AT2", an (x, y)
        tuple of Records; see pipeline.records.pair), the building moves in x and y on coupled
        isolators, and `angle` (degrees, default 0; swept like any parameter) rotates each
        pair counterclockwise; `mu_wall` (default 0; swept alike) is the Coulomb friction
        between slab and wall. The archive then also holds the per-direction peaks (*_xy,
        dimension `direction`) and the largest force per wall (`wall`); peak_* are
        resultants. The same walls on every side (a square or circular moat).
    level (-, any run; swept like any parameter): the intensity, a factor multiplying every
        record's ground acceleration (engine.simulate's scale); the baseline and unconstrained
        blocks repeat per level. factors: None, or (R,) positive factors (-), one per record,
        multiplying each record's acceleration on top of the level (a code suite's MCE_R
        factors): a member runs at factor x level (level 1 when not given). The archive then
        has a `level` coordinate and `record_factor` along record.
    bumper_positions: for a building that twists (its torsion; moat "rectangular"): None,
        its corners against bare walls, or (along the x walls, along the y walls), the
        bumpers' positions (m) from the plan's centre (engine.simulate's); the archive then
        has each contact point's peaks (dimension `point`) and the corners' and rotation's.
    members: instead of a grid, a table of members listed one by one (pipeline.listed: column
        "law" and parameters by name, (K,) for every record or (R, K) per record); the
        archive's dims are then (record, member). No other sweep parameter is given then.
    backend: the engine's time loop (engine.simulate's: None for its default, the compiled
        kernel; "cuda" runs on an NVIDIA GPU, DEVICE_BATCH members a call unless batch_size
        says otherwise, in this process, or on a scheduler's workers started with `--resources
        GPU=1`, one per GPU). The archive's `sweep_arguments` record it when given.
    force: replace an existing `out` that holds another sweep. Without it such an archive is
        kept and SweepError raised before any compute; an archive of this very sweep (the
        same records, dt, building, members and engine: its `configuration_key` attribute)
        is replaced silently, since it holds the same numbers.

    Returns an xarray.Dataset, dims: record, the swept parameters (in the order gap, thickness,
    cavity, strain, n_bumpers, wall_k, cor, then the isolator's), floor (0..N) and story (1..N):
    0-4 and 1-4 for the paper's building. Variables: peak_total_accel (m/s^2; floor),
    peak_interstory_drift (m; story), peak_isolator_disp (m), max_indentation (m),
    max_impact_force (N), n_impacts, impact_energy (J); with baseline, baseline_<same> (record,
    gap, ...) and amplification_total_accel, amplification_interstory_drift (bumpers / no
    bumpers); with unconstrained, unconstrained_<same> (record, ...). Raises SweepError, naming
    the parameter, before any simulation runs.
    """
    o = SweepOptions(**{name: keywords.pop(name) for name in OPTIONS if name in keywords})
    given = sweep_parameters(keywords)  # the rest: swept parameters (SweepError otherwise)
    building = check_building(o.building)
    model = run_model(o.moat, building)
    members, factors = o.members, o.factors
    if members is not None:
        given = {k: v for k, v in given.items() if v is not None}
        if given or o.baseline or o.unconstrained or o.m_eff is not None:
            raise SweepError("members lists every member: give its parameters as its columns, "
                             f"not as {', '.join(given) or 'baseline/unconstrained/m_eff'}")
        grid = listed_grid(members, isolator=building.isolation.law, plan=model.in_plan,
                           intensity=factors is not None)
    elif given["gap"] is None:
        raise SweepError("gap is required (m)")
    else:
        grid = make_grid(impact=o.impact, isolator=building.isolation.law, m_eff=o.m_eff,
                         baseline=o.baseline, unconstrained=o.unconstrained,
                         plan=model.in_plan, intensity=factors is not None, **given)
    # a building that twists' parameters are recorded when given (other archives unchanged)
    recorded = {k: v for k, v in given.items() if v is not None or k not in TORSION_PARAMS}
    arguments = {"members": members, "moat": o.moat} if members is not None else {
        **recorded, "impact": o.impact, "baseline": o.baseline,
        "unconstrained": o.unconstrained, "m_eff": grid.m_eff, "moat": o.moat}
    return execute_sweep(grid, arguments,
                         Conditions(records, o.records_dir, o.dt, building, o.moat, factors,
                                    o.bumper_positions),
                         Compute(o.workers, o.scheduler, o.batch_size, o.quiet, o.backend),
                         Output(o.out, o.work_dir, o.force))


def check_levels(grid, recs, names) -> None:
    """RecordError where the grid's largest intensity level takes a record's PGA beyond what
    earthquakes have recorded (records.plausible.check_level): `kobe*100` is refused, and so
    is level 100 on kobe."""
    from .records.plausible import check_level

    levels = grid.every_member["level"]
    if np.all(np.isnan(levels)):
        return
    top = float(np.nanmax(levels))
    for record, name in zip(recs, names, strict=True):
        check_level(record.pga, top, name)


def completed_sweep():
    """`sweep`, its signature listing the sweep parameters by name (keyword-only, default
    None) for help() and IDEs: what `pipeline.sweep` is. Deriving them imports the impact and
    isolator laws, which `import pipeline` does not."""
    records = inspect.Parameter("records", inspect.Parameter.POSITIONAL_OR_KEYWORD)
    swept = [inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=None)
             for name in DIMENSIONS]
    own = [inspect.Parameter(f.name, inspect.Parameter.KEYWORD_ONLY, default=f.default,
                             annotation=f.type) for f in dataclasses.fields(SweepOptions)]
    sweep.__signature__ = inspect.Signature([records, *swept, *own])
    return sweep


def unconstrained_peaks(records, dt: float | None = None, building=None, workers: int = 1,
                        scheduler=None, records_dir=None, quiet: bool = True, work_dir=None,
                        backend: str | None = None):
    """Peaks of the building without moat wall: a Dataset with dims (record, floor/story).

    Variables as in `sweep` (peak_isolator_disp m, peak_total_accel m/s^2, ...). Recipes use
    it for "gap = 0.9 x unconstrained peak isolator displacement" and as the no-pounding
    reference. backend: the engine's time loop, as `sweep`'s.
    """
    grid = make_grid(None, unconstrained=True)
    ds = execute_sweep(grid, {"unconstrained_only": True},
                       Conditions(records, records_dir, dt, building),
                       Compute(workers, scheduler, quiet=quiet, backend=backend),
                       Output(work_dir=work_dir))
    prefix = "unconstrained_"
    return ds.rename({name: name[len(prefix):] for name in ds.data_vars
                      if name.startswith(prefix)})


def execute_sweep(grid, arguments: dict, conditions: Conditions, compute: Compute,
                  output: Output):
    """Check the rest of the input, open the store (.zarr: Zarr; else NetCDF), run, finish:
    the labelled Dataset with what its peaks mean (pipeline.assess.sweep_variables).
    grid: the members (pipeline.grid.Grid); arguments: the call's, stored in the archive;
    conditions, compute, output: the rest, as `sweep` takes them."""
    records, records_dir, dt, building, moat, factors, bumper_positions = (
        conditions.records, conditions.records_dir, conditions.dt, conditions.building,
        conditions.moat, conditions.factors, conditions.bumper_positions)
    workers, scheduler, batch_size, quiet = (compute.workers, compute.scheduler,
                                             compute.batch_size, compute.quiet)
    out, work_dir, force = output.out, output.work_dir, output.force
    building = check_building(building)
    model = run_model(moat, building)
    dt = check_dt(grid, engine.DEFAULT_DT if dt is None else dt, building)
    workers = check_count("workers", workers, minimum=0)
    cores = os.cpu_count() or 1
    if scheduler is None and workers > cores:
        warnings.warn(PlausibilityWarning(
            f"workers = {workers} on a machine of {cores} core{'s' * (cores != 1)}: the "
            "worker processes share them, the run no faster than with one worker a core"),
            stacklevel=2)
    backend = check_backend(compute.backend, model, workers if scheduler is None else 1)
    if scheduler is not None and not isinstance(scheduler, str) \
            and not hasattr(scheduler, "submit"):
        raise SweepError(f"scheduler must be an address such as 'tcp://host:8786' or a "
                         f"dask.distributed Client, got {scheduler!r}")
    if model.in_plan:
        recs, names = resolve_pairs(records, records_dir)
    else:
        recs, names = resolve_records(records, records_dir)
    factors = checked_factors(factors, len(recs))
    if factors is None:  # levels on the records as they are (a study's levels multiply its
        check_levels(grid, recs, names)  # suite's factors: its design bounds them)
    if grid.table is not None:
        check_records(grid, len(recs))
    if batch_size is None:
        batch_size = default_batch_size(grid.n_members, len(recs), workers) \
            if backend != "cuda" else min(grid.n_members, DEVICE_BATCH)
    batch_size = check_count("batch_size", batch_size, minimum=1)
    out = check_out(out)
    arguments = plain({**arguments, "records": names, "dt": dt,
                       **({} if factors is None else {"factors": factors}),
                       **({} if backend is None else {"backend": backend})})
    if bumper_positions is not None:
        try:
            model.check("bumper_positions", True)
        except engine.EngineError as err:
            raise SweepError(str(err)) from None
        bumper_positions = tuple(tuple(float(x) for x in np.ravel(side))
                                 for side in bumper_positions)
        arguments["bumper_positions"] = [list(side) for side in bumper_positions]
    run = Run(recs, names, dt, building, moat, factors, arguments, bumper_positions, backend)
    new_store = None
    if out is not None and out.suffix == ".zarr":
        # the outermost folder this run creates, removed again if no batch runs
        new_store = next((p for p in reversed((out, *out.parents)) if not p.exists()), None)
        store = ZarrStore(grid, run, out, batch_size, force, derive=derived_variables)
    else:
        store = NetCDFStore(grid, run, out, work_dir, derive=derived_variables)
        if out is not None:
            guard(out, store.key, force, python=True)
    try:
        execute(store, workers=workers, scheduler=scheduler, batch_size=batch_size,
                quiet=quiet, device=backend == "cuda")
    except SweepError:  # refused before any batch ran (e.g. no cluster): leave nothing
        if new_store is not None and not store.done.any():
            shutil.rmtree(new_store, ignore_errors=True)
        raise
    return store.finish()


DEVICE_BATCH = 1 << 20
"""Members per engine call on the device (backend "cuda"): a launch of 10^6 threads fills an
H100 or H200 many times over (132 multiprocessors of up to 2048 threads), and its arrays, about
2 KB a member, take 2 GB of the device's memory."""


def check_backend(backend: str | None, model, local_workers: int) -> str | None:
    """The engine's time loop a sweep asked for (None: the engine's default), checked before
    any record is read: SweepError in one line for a name the engine does not know, a device
    that cannot run here, a model the device does not run, or local worker processes sharing
    this machine's GPU (local_workers: those the sweep would start; 1 on a scheduler)."""
    if backend is None:
        return None
    if backend == "cuda" and local_workers >= 2:
        raise SweepError("backend 'cuda' runs one process per GPU: give workers=1 (--workers "
                         "1: this process, on its GPU), or a scheduler whose workers hold one "
                         "GPU each (dask worker --resources GPU=1, one per GPU)")
    from engine.backends import loop_of

    try:
        loop_of(model, backend)
    except engine.EngineError as err:
        raise SweepError(str(err)) from None
    return backend


def checked_factors(factors, n_records: int):
    """(R,) float intensity factors of the records, or None; SweepError for anything but R
    positive finite numbers."""
    if factors is None:
        return None
    try:
        array = np.asarray(factors, dtype=float)
    except (TypeError, ValueError):
        raise SweepError(f"factors must be {n_records} numbers, one per record, got "
                         f"{factors!r}") from None
    if array.shape != (n_records,):
        raise SweepError(f"factors must be {n_records} numbers, one per record, got shape "
                         f"{array.shape}")
    if not np.all(np.isfinite(array) & (array > 0)):
        raise SweepError(f"factors must be positive and finite (-), got {array.tolist()}")
    return array


def scale_to_displacement(records, displacement: float | None = None,
                          limits: tuple[float, float] | None = None, **options):
    """Scale records so that the building without wall reaches `displacement` (m; default
    pipeline.motions.scaling.DEFAULT_DISPLACEMENT, 0.30 m) with factors within `limits` (default
    DEFAULT_LIMITS, 0.2-5): see pipeline.motions.scaling.scale_to_displacement (options: dt,
    building,
    records_dir, tolerance, quiet). Returns a pipeline.motions.scaling.ScaledSuite."""
    return scale(records, DEFAULT_DISPLACEMENT if displacement is None else displacement,
                 DEFAULT_LIMITS if limits is None else limits, **options)
