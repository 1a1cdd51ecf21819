"""Study pipeline: records, parameter grids, dask-parallel engine runs, NetCDF archives.

    import pipeline
    ds = pipeline.sweep(records=["kobe", "pacoima"], gap=[0.15, 0.30, 0.45],
                        n_bumpers=[4, 8], baseline=True, out="results/gap.nc")

Data flows one way: records (records.py: AT2 files, the embedded library, lookup by name) +
grid (grid.py: parameters checked against the impact laws' declarations, one member record
per simulation) -> engine batches, here or on dask, resumable (run.py) -> labelled Dataset
with its provenance (archive.py, provenance.py) -> NetCDF (archive.py). histories.py keeps
time histories of a few configurations; scaling.py scales records to a design displacement;
errors.py holds SweepError. Imports happen inside the
functions, so that light entry points such as `python -m pipeline.records` load neither
xarray nor dask.
"""
from __future__ import annotations

__all__ = ["SweepError", "scale_to_displacement", "sweep", "unconstrained_peaks"]


def sweep(records, *, gap=None, thickness=None, cavity=None, strain=None, n_bumpers=None,
          wall_k=None, cor=None, impact: str = "bumper", dt: float | None = None,
          workers: int = 1, scheduler=None, out=None, baseline: bool = False,
          unconstrained: bool = False, building=None, m_eff: float | None = None,
          batch_size: int | None = None, records_dir=None, quiet: bool = False,
          work_dir=None):
    """Simulate every combination of the parameters under every record; label the peaks.

    records: paper keys ("kobe", "sylmar_converter", "olive_view", "pacoima"), library names,
        AT2 paths (see pipeline.records.load_record) or Record objects; one or a list.
    Every parameter after `records` is given by keyword.
    gap (m, the seismic gap before any bumper), thickness (m), cavity (m, depth of the wall
        cavity holding each bumper, paper 5.3), strain (-), n_bumpers (-), wall_k (N/m;
        N/m^1.5 for jankowski and hertzdamp), cor (-): a scalar is held fixed (scalar
        coordinate), a sequence is swept (a dimension). None takes the impact law's
        declared default (engine.impact.LAWS[impact].PARAMETERS, where each law states what
        wall_k means for it); thickness, cavity, strain, n_bumpers apply to bumpers only.
    impact: "bumper" (the paper's rubber bumpers, default), "linear", "jankowski", "hertzdamp".
    dt: integration step (s), default engine.DEFAULT_DT; refused at or above the stability
        limit (engine.stable_dt).
    workers: 0 or 1 (default) runs in this process, the compiled kernel spreading each batch's
        members over every core with threads (measured the fastest on one machine: no worker
        start-up, no copies); >= 2 starts that many local dask worker processes, one thread
        each. Worker processes are spawned: a script calling sweep with workers >= 2 needs
        the `if __name__ == "__main__":` guard.
    scheduler: a dask.distributed scheduler address (or Client) to run on instead.
    out: NetCDF path, written atomically; finished batches are kept in `<out>.work/` so that a
        rerun after a crash computes only what is missing; the folder goes once out is written.
        A path ending in `.zarr` writes a Zarr store instead, for sweeps too large for one
        file or the client's memory: workers write their batches into it directly, it is its
        own resume record, and the return value is the store opened lazily (see
        pipeline.zarr_store).
    baseline: also run the bare wall without bumpers (the linear law at its defaults, k 2.5e9
        N/m, COR 0.5) once per (record, gap) at the full gap; adds baseline_* and
        amplification_* variables.
    unconstrained: also run each record without wall; adds unconstrained_* variables.
    building: engine.Building (default: the paper's); m_eff: effective impact mass (kg;
        default: the declared one, 320 t, the base slab).
    batch_size: members per engine call (default: pipeline.run.default_batch_size).
    records_dir: folder of AT2 files for the records' lookup; quiet: no progress bar.
    work_dir: a folder that keeps finished batches (default: `<out>.work` when out is given,
        removed once out is written; an explicit one is kept, and may be shared by several
        sweeps). Ctrl-C raises pipeline.errors.Interrupted (a KeyboardInterrupt) saying how
        many simulations are kept there; the same call again computes only the rest.

    Returns an xarray.Dataset, dims: record, the swept parameters (in the order gap,
    thickness, cavity, strain, n_bumpers, wall_k, cor), floor (0-4) or story (1-4). Variables:
    peak_total_accel (m/s^2; floor), peak_interstory_drift (m; story), peak_isolator_disp (m),
    max_indentation (m), max_impact_force (N), n_impacts, impact_energy (J); with baseline,
    baseline_<same> (record, gap, ...) and amplification_total_accel,
    amplification_interstory_drift (bumpers / no bumpers); with unconstrained,
    unconstrained_<same> (record, ...). Raises SweepError, naming the parameter, before any
    simulation runs.
    """
    from .errors import SweepError
    from .grid import make_grid

    if gap is None:
        raise SweepError("gap is required (m)")
    grid = make_grid(gap, thickness, strain, n_bumpers, wall_k, cor, impact=impact,
                     m_eff=m_eff, baseline=baseline, unconstrained=unconstrained,
                     cavity=cavity)
    arguments = {"gap": gap, "thickness": thickness, "cavity": cavity, "strain": strain,
                 "n_bumpers": n_bumpers, "wall_k": wall_k, "cor": cor, "impact": impact,
                 "baseline": baseline, "unconstrained": unconstrained, "m_eff": grid.m_eff}
    return _execute(grid, records, dt, workers, scheduler, out, building, batch_size,
                    records_dir, quiet, arguments, work_dir)


def unconstrained_peaks(records, dt: float | None = None, building=None, workers: int = 1,
                        scheduler=None, records_dir=None, quiet: bool = True, work_dir=None):
    """Peaks of the building without moat wall: a Dataset with dims (record, floor/story).

    Variables as in `sweep` (peak_isolator_disp m, peak_total_accel m/s^2, ...). Recipes use
    it for "gap = 0.9 x unconstrained peak isolator displacement" and as the no-pounding
    reference.
    """
    from .grid import make_grid

    grid = make_grid(None, unconstrained=True)
    ds = _execute(grid, records, dt, workers, scheduler, None, building, None, records_dir,
                  quiet, {"unconstrained_only": True}, work_dir)
    prefix = "unconstrained_"
    return ds.rename({name: name[len(prefix):] for name in ds.data_vars
                      if name.startswith(prefix)})


def _execute(grid, records, dt, workers, scheduler, out, building, batch_size, records_dir,
             quiet, arguments, work_dir=None):
    """Check the rest of the input, run, label, archive."""
    import shutil

    import engine

    from .archive import build_dataset, check_out, check_work_dir, write_netcdf
    from .errors import SweepError, check_count
    from .grid import check_dt
    from .provenance import plain
    from .records import RecordError, resolve_records
    from .run import default_batch_size, run

    building = engine.Building() if building is None else building
    if not isinstance(building, engine.Building):
        raise SweepError(f"building must be an engine.Building, got {type(building).__name__}")
    dt = check_dt(grid, engine.DEFAULT_DT if dt is None else dt, building)
    workers = check_count("workers", workers, minimum=0)
    if scheduler is not None and not isinstance(scheduler, str) \
            and not hasattr(scheduler, "submit"):
        raise SweepError(f"scheduler must be an address such as 'tcp://host:8786' or a "
                         f"dask.distributed Client, got {scheduler!r}")
    try:
        recs, names = resolve_records(records, records_dir)
    except RecordError as err:
        raise SweepError(str(err)) from err
    if batch_size is None:
        batch_size = default_batch_size(grid.n_members, len(recs), workers)
    batch_size = check_count("batch_size", batch_size, minimum=1)
    out = check_out(out)
    if out is not None and out.suffix == ".zarr":
        from .run import context_key
        from .zarr_store import run_zarr

        arguments = plain({**arguments, "records": names, "dt": dt})
        contexts = [context_key(rec, dt, building) for rec in recs]
        return run_zarr(grid, recs, names, dt, building, arguments, out, contexts,
                        workers=workers, scheduler=scheduler, batch_size=batch_size,
                        quiet=quiet)
    own_work_dir = work_dir is None and out is not None
    if own_work_dir:
        work_dir = out.with_name(out.name + ".work")
    work_dir = check_work_dir(work_dir)

    results = run(grid, recs, dt, building, workers=workers, scheduler=scheduler,
                  work_dir=work_dir, batch_size=batch_size, quiet=quiet)
    arguments = plain({**arguments, "records": names, "dt": dt})
    ds = build_dataset(grid, recs, results, dt, building, names, arguments)
    if out is not None:
        write_netcdf(ds, out)
    if own_work_dir:
        shutil.rmtree(work_dir, ignore_errors=True)
    return ds


def scale_to_displacement(records, displacement: float = 0.30,
                          limits: tuple[float, float] = (0.2, 5.0), **options):
    """Scale records so that the building without wall reaches `displacement` (m): see
    pipeline.scaling.scale_to_displacement (options: dt, building, records_dir, tolerance,
    quiet). Returns a pipeline.scaling.ScaledSuite."""
    from .scaling import scale_to_displacement as scale

    return scale(records, displacement, limits, **options)


def __getattr__(name):
    if name == "SweepError":
        from .errors import SweepError

        return SweepError
    raise AttributeError(f"module 'pipeline' has no attribute {name!r}")
