"""Running a sweep's simulations: one executor, two stores.

executor.py runs batches (batches.py: one engine call each) in this process or on dask
(dask_client.py), with a progress line (pipeline.progress) and Ctrl-C turned into
pipeline.errors.Interrupted. Where the results go is a store's business, behind one small
interface (executor.Store): netcdf_store.py gathers peaks here, keeps finished batches in a
resumable work folder and writes one NetCDF archive at the end; zarr_store.py has workers
write their batches' chunk regions of a Zarr store, its own resume record. keys.py makes every
key a resumed run is matched by. Nothing here is imported by `import pipeline`.
"""
