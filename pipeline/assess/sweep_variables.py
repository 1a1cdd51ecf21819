"""What a sweep's peaks mean, as variables of its archive: the amplification ratios bumpers /
no bumpers, the stories' peak ductility, and every block's validity flags (the rules of
pipeline.assess.validity, at their default limits). Computed from the labelled Dataset the
archive builds (pipeline.archive.build_dataset, which adds them: it is given
`derived_variables`), lazily when the Dataset is lazy (a Zarr store's)."""
from __future__ import annotations

import numpy as np
import xarray as xr

import engine
from engine.impact import LAWS
from engine.results import Quantity
from pipeline.archive import block_long_name

from .derived import bumper_stress, largest_floor_accel
from .validity import (
    FLAGS,
    Limits,
    bumper_strain_exceeds,
    bumper_stress_exceeds,
    floor_accel_exceeds,
)

STORY_DUCTILITY = Quantity("peak_story_ductility", "1", "peak story ductility (peak "
                           "interstory deflection / yield deflection F_i / k_i)", "story")
"""Derived from peak_interstory_drift when the building's stories yield."""
AMPLIFICATION = {
    "amplification_total_accel": ("peak_total_accel",
                                  "peak floor acceleration, bumpers / no bumpers (Fig. 14)"),
    "amplification_interstory_drift": ("peak_interstory_drift",
                                       "peak interstory deflection, bumpers / no bumpers "
                                       "(Fig. 15)"),
}
"""The ratios with bumpers over the bare wall (the baseline block): name -> (the peak, its
long name). The plain ratio of the two peaks, as the paper's figures plot it."""


def derived_variables(ds: xr.Dataset, building: engine.Building, grid=None) -> dict:
    """Variables computed from a sweep's peaks, name -> (DataArray, the peak whose dims and
    chunks it shares), lazy when ds is: the amplification ratios bumpers / no bumpers when ds
    has a baseline block; the peak story ductility (peak drift / yield drift F_i / k_i) of
    every block when the building's stories yield; with the grid (pipeline.grid.Grid), every
    block's validity flags (`validity_variables`)."""
    derived = {} if grid is None else validity_variables(ds, grid, building)
    if "baseline_peak_total_accel" in ds:
        for name, (peak, long_name) in AMPLIFICATION.items():
            ratio = (ds[peak] / ds["baseline_" + peak]).transpose(*ds[peak].dims)
            ratio.attrs = {"units": "1", "long_name": long_name}
            derived[name] = (ratio, peak)
    if building.story_yield_drift is not None:
        yield_drift = xr.DataArray(building.story_yield_drift, dims="story")
        for drift in [name for name in ds.data_vars
                      if name.endswith("peak_interstory_drift")]:
            prefix = drift[: -len("peak_interstory_drift")]
            ductility = (ds[drift] / yield_drift).transpose(*ds[drift].dims)
            ductility.attrs = {"units": STORY_DUCTILITY.units,
                               "long_name": block_long_name(STORY_DUCTILITY, prefix)}
            derived[prefix + "peak_story_ductility"] = (ductility, drift)
    return derived


def pad_force(ds: xr.Dataset, prefix: str) -> xr.DataArray:
    """The force (N) the bumpers' stress is judged on, as if the wall's n_bumpers shared it:
    the largest impact force; for a building that twists, the largest over the contact points
    of a point's force times the points on its wall (a point carries n_bumpers / points of
    them), which is no less where the slab turns and loads one pad more than its share."""
    if prefix + "max_point_force" not in ds:
        return ds[prefix + "max_impact_force"]
    wall = ds["point_wall"].values
    per_wall = xr.DataArray([np.sum(wall == w) for w in wall], dims="point")
    return (ds[prefix + "max_point_force"] * per_wall).max("point")


def validity_variables(ds: xr.Dataset, grid, building: engine.Building) -> dict:
    """Every block's `invalid_*` flags, name -> (int8 DataArray over the block's dims, 1 where
    the run left the model's range; the peak it follows), lazy when ds is (the rules of
    pipeline.assess.validity at its default limits: the bumpers' calibration stress and
    strain where the block has bumpers, the rigid-floor acceleration, a collapse where the
    building can collapse; a sweep knows no story or wall capacity: those are not checked,
    and the archive's validity_limits says so). grid: the sweep's pipeline.grid.Grid, whose
    members say which runs have bumpers, how many and how thick."""
    limits = Limits()
    default_area = LAWS["bumper"].PARAMETERS["area"].default
    out, start = {}, 0
    for block in grid.blocks:
        part = slice(start, start + block.size)
        start += block.size
        p = block.prefix
        force = ds[p + "max_impact_force"]

        def column(name, part=part):  # (R, M): the members' column, no whole record copied
            return np.stack([grid.members_of(r)[part][name] for r in range(ds.sizes["record"])])

        def along(values, force=force):  # (R, M) -> the block's (record, *dims)
            return xr.DataArray(values.reshape(force.shape), dims=force.dims)

        def flag(name, value, peak, p=p, dims=force.dims):
            value = value.astype(np.int8).transpose(*dims)
            value.attrs = {"units": "1", "long_name": f"1 where {FLAGS[name]}"}
            out[p + name] = (value, peak)

        flag("invalid_floor_accel",
             floor_accel_exceeds(largest_floor_accel(ds[p + "peak_total_accel"]),
                                 limits.floor_accel),
             p + "peak_total_accel")
        bumper = column("law") == "bumper"
        if bumper.any():
            # no bumpers: infinitely many, infinitely thick (never stressed, never strained)
            area = column("area")
            area = along(np.where(np.isnan(area), default_area, area))
            n_bumpers = along(np.where(bumper, column("n_bumpers"), np.inf))
            flag("invalid_bumper_stress",
                 bumper_stress_exceeds(bumper_stress(pad_force(ds, p), n_bumpers, area),
                                       limits.bumper_stress),
                 p + "max_impact_force")
            thickness = along(np.where(bumper, column("thickness"), np.inf))
            flag("invalid_bumper_strain",
                 bumper_strain_exceeds(ds[p + "max_indentation"], thickness,
                                       limits.bumper_strain),
                 p + "max_indentation")
        if p + "collapsed" in ds:
            flag("invalid_collapse", ds[p + "collapsed"], p + "collapsed")
    ds.attrs["validity_limits"] = limits.describe()
    return out
