"""Commands on a sweep's archive, not recipes: `bumpers export` (the peaks as a CSV table, or
as a pelicun demand sample) and `bumpers plot` (a peak against a swept dimension), on the
NetCDF and Zarr archives that pipeline.sweep and `bumpers sweep` write.
"""
