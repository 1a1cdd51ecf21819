"""What pounding and the isolators' largest displacements damage that FEMA P-58's component
inventory does not hold: the moat's cover and wall, its bumpers, the bearings and the utilities
crossing the isolation plane. Pure functions of peaks (engine.results.PEAKS, SI).

Each item of the moat inventory (pipeline/data/moat_inventory.csv, or the building's own with
the same columns) is repaired or replaced at its unit cost times its quantity once its trigger
holds in a run:
- `contact`: the slab struck a wall (n_impacts > 0);
- `crushed`: a bumper was crushed (max_indentation beyond the crush indentation delta_u; only
  where the moat has bumpers);
- `beyond_d_tm`: the isolators passed the total maximum displacement D_TM, the displacement
  the bearings and the utility connections are made for (ASCE 7-22 17.5.3's D_TM).
The quantities follow the building (`per`): the plan's perimeter (m; a square plan of the floor
area), the bearings (one under each column of a square grid of BAY spans), the bumpers (n on
each of the moat's 4 walls; a circular moat's bumpers are counted alike, as 4 sets of n), or
the building (one). Every cost is a stated allowance in USD of
2011 (FEMA P-58's year), not a FEMA P-58 consequence function: give the building's own table
where they are known.
"""
from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

from .derived import crushed

MOAT_INVENTORY = Path(__file__).resolve().parents[1] / "data" / "moat_inventory.csv"
"""The default moat inventory (stated allowances; see the module docstring)."""
BAY = 7.5
"""m: the column spacing of the square grid the bearings stand under (a stated choice: a 30 m
square plan has 5 x 5 = 25 bearings)."""
WALLS = 4
"""The walls of the rectangular moat, each with its n bumpers."""
TRIGGERS = ("contact", "crushed", "beyond_d_tm")
"""What a moat item's damage follows (the module docstring)."""
PER = ("perimeter_m", "bearing", "bumper", "building")
"""What a moat item's quantity counts."""


def read(path=None) -> list[dict]:
    """The moat inventory's rows (item, trigger, per, unit_cost USD 2011, description) from
    `path` (default MOAT_INVENTORY); ValueError naming the row and column that is wrong."""
    path = Path(path) if path is not None else MOAT_INVENTORY
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        raise ValueError(f"{path}: cannot read it ({e})") from None
    for i, row in enumerate(rows, start=2):  # line 1 is the header
        if row.get("trigger") not in TRIGGERS:
            raise ValueError(f"{path} line {i}: trigger must be one of {', '.join(TRIGGERS)}, "
                             f"got {row.get('trigger')!r}")
        if row.get("per") not in PER:
            raise ValueError(f"{path} line {i}: per must be one of {', '.join(PER)}, got "
                             f"{row.get('per')!r}")
        try:
            row["unit_cost"] = float(row["unit_cost"])
        except (KeyError, TypeError, ValueError):
            raise ValueError(f"{path} line {i}: unit_cost must be a number (USD 2011)") from None
        if not (math.isfinite(row["unit_cost"]) and row["unit_cost"] >= 0):
            raise ValueError(f"{path} line {i}: unit_cost must be >= 0 (USD 2011)")
    return rows


def quantities(floor_area: float, bumpers) -> dict:
    """per -> the quantity of an item counted that way: the perimeter (m) of a square plan of
    floor_area (m^2), the bearings under a square grid of BAY spans, the bumpers (`bumpers`
    on each wall, broadcast), one building."""
    side = math.sqrt(floor_area)
    columns = round(side / BAY) + 1
    return {"perimeter_m": 4.0 * side, "bearing": float(columns * columns),
            "bumper": WALLS * np.asarray(bumpers, float), "building": 1.0}


def triggered(peaks, d_tm: float, delta_u: float, bumpers) -> dict:
    """trigger -> bool array of the runs where it holds: peaks (n_impacts, max_indentation,
    peak_isolator_disp, broadcast alike), the total maximum displacement d_tm (m), the
    bumpers' crush indentation delta_u (m), `bumpers` per wall (0: none, broadcast)."""
    has = np.asarray(bumpers, float) > 0
    return {"contact": np.asarray(peaks["n_impacts"]) > 0,
            "crushed": crushed(peaks["max_indentation"], delta_u) & has,
            "beyond_d_tm": np.asarray(peaks["peak_isolator_disp"]) > d_tm}


def costs(rows, peaks, *, d_tm: float, delta_u: float, bumpers, floor_area: float):
    """Each item's repair cost (USD 2011) in each run: (items, *runs) with the items in the
    order of `rows` (read); bumpers per wall broadcast against the runs (0 where none)."""
    hit = triggered(peaks, d_tm, delta_u, bumpers)
    count = quantities(floor_area, bumpers)
    shape = np.broadcast_shapes(*(np.shape(v) for v in hit.values()))
    return np.stack([np.broadcast_to(hit[r["trigger"]] * (count[r["per"]] * r["unit_cost"]),
                                     shape) for r in rows])


def mean_given_no_collapse(item_costs, standing, share):
    """Each item's mean cost (USD 2011) over the runs that did not collapse, each run weighed
    by its pair's share of the weight (its earthquake's share once): item_costs (items, R,
    ...), standing (R, ...) bool, share (R,) summing to 1 -> (items, ...); 0 where no run
    stands (the collapse's replacement then holds everything)."""
    w = np.asarray(share, float).reshape((-1,) + (1,) * (np.ndim(standing) - 1)) * standing
    total = w.sum(axis=0)
    return np.where(total > 0, (np.asarray(item_costs) * w).sum(axis=1)
                    / np.where(total > 0, total, 1.0), 0.0)


def realizations(run_costs, standing, share, samples: int, seed: int = 1):
    """Each realization's moat cost (USD 2011) given no collapse: realization k takes the cost
    of one standing run, drawn by the runs' weights (their pairs' shares), stratified (the
    k-th of `samples` equal slices of the weights' cumulative sum, in an order fixed by
    `seed`), so that the realizations' mean is the weighted mean to the slices' width and a
    run's costs stay together (a contact and the isolators past D_TM fall on one realization
    only where one run had both). The same k takes the same slice in every configuration
    (common random numbers). run_costs (R, ...) and standing (R, ...) bool, share (R,) ->
    (..., samples); 0 where no run stands. Independent of the FEMA P-58 realization it is
    added to (a stated simplification: the moat's damage and the building's are drawn
    apart)."""
    order = np.random.default_rng(seed).permutation(samples)
    u = (order + 0.5) / samples  # (samples,) in (0, 1), every slice once
    costs_ = np.moveaxis(np.asarray(run_costs, float), 0, -1)  # (..., R)
    w = np.moveaxis(np.asarray(share, float).reshape((-1,) + (1,) * (np.ndim(standing) - 1))
                    * standing, 0, -1)
    total = w.sum(axis=-1, keepdims=True)
    cdf = np.cumsum(w, axis=-1) / np.where(total > 0, total, 1.0)
    out = np.zeros(costs_.shape[:-1] + (samples,))
    for index in np.ndindex(costs_.shape[:-1]):
        if total[index][0] > 0:
            pick = np.minimum(np.searchsorted(cdf[index], u, side="right"), cdf.shape[-1] - 1)
            out[index] = costs_[index][pick]
    return out
