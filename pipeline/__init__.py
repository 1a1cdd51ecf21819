"""Study pipeline: records, parameter grids, engine runs here or on dask, labelled archives.

    import pipeline
    ds = pipeline.sweep(records=["kobe", "pacoima"], gap=[0.15, 0.30, 0.45],
                        n_bumpers=[4, 8], baseline=True, out="results/gap.nc")

Data flows one way, each fact in one place: records -> what shakes the building -> the grid
of members -> the executor -> labelled archives -> what a result means.
- records/ : AT2 and text files, the embedded library, the paper's records, pairs, lookup;
- motions/ : what shakes the building: spectra, the code's targets and isolation design,
  scaling rules (rules/, a registry), code suites at levels of intensity, intensity measures;
- members.py : what a member carries, one declaration (a row per number: the wall's, the
  isolator's and the excitation's parameters, derived from the laws' declarations) and the
  excitation's rule; grid.py : a set of members as one Grid (the sweep's combinations, the
  baseline and unconstrained blocks); listed.py : members listed one by one, for every record
  or per record (a Grid too, as histories.py's named configurations are);
- execute/ : running the members: one executor (here or on dask, Ctrl-C ->
  errors.Interrupted), what a run is (run.py), its batches, its keys, and two stores behind
  one interface (netcdf_store.py: a resumable work folder, one NetCDF at the end; zarr_store.py:
  workers write chunk regions);
- archive.py : labelled Datasets (units and long names from the declarations), atomic NetCDF;
  provenance.py : the global attributes; writing.py : atomic replacement and configuration
  keys; suite_labels.py : a code suite's variables in the archives; histories.py : time
  histories of a few named configurations;
- building_file.py : a building from a file or NAME=VALUE settings; cluster.py : connecting to
  a dask cluster and refusing an unfit one; checks.py : the shared input checks; progress.py :
  the progress line; errors.py : SweepError, ClusterError, Interrupted (a leaf);
- assess/ : what a result means, pure functions over arrays: derived responses, validity,
  outcomes and weights, fragility;
- orchestration.py : the sweep itself (`sweep`, `unconstrained_peaks`,
  `scale_to_displacement`): checks the call, builds the grid, runs it into a store, has assess
  say what the peaks mean and the archive label it.
The packages stand in that order, each importing only from those before it (tests/test_layout.py
keeps it so): records and the shared leaves (errors, checks, writing, building_file,
progress) -> motions -> members, grid, listed, provenance, cluster, execute -> archive (and
the stores that write archives, the suites' labels) -> assess -> the orchestrations
(orchestration.py, histories.py). This face loads nothing: `import pipeline` imports no module
of the project, so that light entry points such as `python -m pipeline.records` load neither
xarray nor dask; the public names are the orchestration's, imported on first use.
"""
from __future__ import annotations

__all__ = ["SweepError", "scale_to_displacement", "sweep", "unconstrained_peaks"]


def __getattr__(name):
    if name == "sweep":
        from .orchestration import completed_sweep

        globals()["sweep"] = completed_sweep()
        return globals()["sweep"]
    if name in ("scale_to_displacement", "unconstrained_peaks"):
        from . import orchestration

        return getattr(orchestration, name)
    if name == "SweepError":
        from .errors import SweepError

        return SweepError
    raise AttributeError(f"module 'pipeline' has no attribute {name!r}")


def __dir__():
    return sorted({*globals(), *__all__})
