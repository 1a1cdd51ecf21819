"""Torsion (beyond the paper): the slab's corners, an eccentric mass, bearings where they stand,
and the force on each bumper.

The paper's building in plan on a rectangular slab (--plan-m, default 30 x 20 m) that can
twist (engine/torsion.py: three degrees of freedom per level, a 4 x 4 grid of bearings, each
a sixteenth of the isolator), its mass centre off the plan's centre by a fraction e of each
plan dimension (e_x = e b_x, e_y = e b_y; 0, 5% and 10%: 5% is ASCE 7-22's accidental
eccentricity, section 17.5.3.3), under the FEMA P695 far-field pairs scaled to the site's
MCE_R (pipeline.motions.code_suite, ASCE 7-22 chapter 17 by default) at incidence angles 0-165
degrees every 15. At each eccentricity the building runs without wall, against the bare wall
(the paper's linear law, shared by the slab's two corners on each side) and with the paper's
bumpers (--pads per wall, evenly spaced, each one 150 x 150 x 50 mm pad) at clear gaps of
0.6, 0.8 and 1.0 times the code's D_M and at its D_TM for that eccentricity (17.5.3.3's
formula: the actual eccentricity plus the accidental 5%, at least 1.15 D_M;
pipeline.motions.torsion).

What it reports, over pairs and angles (each pair weighing its earthquake's share once: the
suite's record_weight): how much farther the worst corner travels than the centre without
wall (median and 84th percentile), against the code's D_TM / D_M; how often the worst corner
passes the code's D_TM; how the force concentrates on one bumper (the worst pad's peak over
its wall's peak total, 1 / pads when shared equally, 1 when one pad takes it all), and the
bare wall's corner likewise; each where contact happens, the runs without contact reported
beside. Verdicts state the code's assumption and the issue's claim with their quantifiers
(verdicts.py).
"""
from __future__ import annotations

import dataclasses
import json

import numpy as np

import engine
from engine.torsion import DEFAULT_GRID

from ..common.options import add_bound, chosen_pairs, scaled_suite, site_options
from ..common.paper import AREA, DELTA_U, N_BUMPERS, THICKNESS
from ..common.recipe import Recipe, provenance, run_options
from .figure import caption, plot  # noqa: F401 - caption: the recipe's caption
from .verdicts import check

PLAN = (30.0, 20.0)
"""m: the default slab (b_x, b_y): 600 m^2 a floor, about the paper's 320 t floors."""
ECCENTRICITIES = (0.0, 0.05, 0.10)
"""The mass centre's offset as a fraction of each plan dimension."""
QUICK_ECCENTRICITIES = (0.0, 0.10)
QUICK_PAIRS = 2
PADS = 2
"""Pads per wall by default (the design study's recommended layout: two on its wall)."""
GAP_FRACTIONS = (0.6, 0.8, 1.0)
"""Clear gaps as fractions of the code's D_M besides its D_TM: the centre reaches a median 0.84
D_M at the MCE_R without wall (0.69-1.05, 16th-84th percentile; `free_peak_isolator_disp`), so
that the narrower gaps are hit by most pairs and D_M and D_TM by the strongest."""
QUICK_GAP_FRACTIONS = (0.6,)
BARRIERS = ("bare wall", "bumpers")
ORBIT_EVERY = 20  # steps between the orbit's samples (10 ms)


def angles(quick: bool) -> np.ndarray:
    """Incidence angles in degrees: 0-165 every 15 (quick: 0, 45, 90)."""
    return np.array((0.0, 45.0, 90.0)) if quick else np.arange(0.0, 180.0, 15.0)


def options(p) -> None:
    site_options(p)
    add_bound(p)
    p.add_argument("--plan-m", type=float, nargs=2, default=PLAN, metavar=("BX", "BY"),
                   help=f"the slab's plan dimensions along x and y, m (default "
                        f"{PLAN[0]:g} {PLAN[1]:g})")
    p.add_argument("--pads", type=int, default=PADS, metavar="N",
                   help=f"bumpers per wall, evenly spaced along it (default {PADS})")


def pad_positions(plan, pads: int) -> tuple[np.ndarray, np.ndarray]:
    """The pads' positions (m from the plan's centre) along the x walls (their y) and the y
    walls (their x): the middles of `pads` equal parts of each side."""
    b_x, b_y = plan
    parts = (np.arange(pads) + 0.5) / pads - 0.5
    return parts * b_y, parts * b_x


def members(gaps, thetas) -> dict:
    """The members of one eccentricity (pipeline.listed): per angle, no wall, then per gap
    (m) the bare wall and the bumpers."""
    law, gap, thickness = ["none"], [np.nan], [np.nan]
    for g in gaps:
        law += ["linear", "bumper"]
        gap += [g, g]
        thickness += [np.nan, THICKNESS]
    per_angle = len(law)
    return {"law": np.tile(law, thetas.size), "gap": np.tile(gap, thetas.size),
            "thickness": np.tile(thickness, thetas.size),
            "angle": np.repeat(thetas, per_angle)}


def compute(args):
    from pipeline import sweep
    from pipeline.errors import SweepError
    from pipeline.motions.code_suite import describe
    from pipeline.motions.torsion import total_maximum_displacement

    plan = tuple(float(b) for b in args.plan_m)
    if not (min(plan) > 0 and args.pads >= 1):
        raise SweepError(f"--plan-m needs two positive lengths and --pads one pad at least, "
                         f"got {plan} and {args.pads}")
    pairs, names = chosen_pairs(args, QUICK_PAIRS)
    suite = scaled_suite(args, pairs, names)
    if not suite.pairs:
        raise SweepError("the scaling rule kept no pair")
    if not args.quiet:
        print("torsion:", describe(suite), flush=True)
    d_m = suite.design.d_m
    thetas = angles(args.quick)
    eccs = np.array(QUICK_ECCENTRICITIES if args.quick else ECCENTRICITIES)
    fractions = QUICK_GAP_FRACTIONS if args.quick else GAP_FRACTIONS
    positions = pad_positions(plan, args.pads)
    building = dataclasses.replace(suite.building, torsion=engine.Torsion(plan_size=plan))
    # one sweep: per eccentricity (the members' accidental eccentricity, engine.torsion.shifted)
    # and angle, no wall, then the bare wall and the bumpers at each gap, D_TM the code's for
    # that eccentricity
    code = [total_maximum_displacement(d_m, plan, (e * plan[0], e * plan[1])) for e in eccs]
    tables = [members([*(f * d_m for f in fractions), d_tm["d_tm"]], thetas) for d_tm in code]
    table = {name: np.concatenate([t[name] for t in tables]) for name in tables[0]}
    table["accidental_eccentricity"] = np.repeat(eccs, tables[0]["law"].size)
    table["n_bumpers"] = np.where(table["law"] == "bumper", float(args.pads), np.nan)
    swept = sweep(suite.pairs, moat="rectangular", factors=suite.factors, members=table,
                  bumper_positions=positions, **{**run_options(args), "building": building})
    gaps = [*(f"{f:g} D_M" if f != 1 else "D_M" for f in fractions), "D_TM"]
    ds = dataset(swept, code, suite, thetas, eccs, positions, gaps, fractions, args)
    ds = ds.assign(orbit_variables(suite, building, eccs[-1], args, engine))
    return ds.assign_attrs({**provenance(swept), **ds.attrs})


PER_RUN = ("peak_isolator_disp", "peak_corner_disp", "peak_rotation", "max_impact_force",
           "n_impacts", "peak_total_accel")


def dataset(swept, code, suite, thetas, eccs, positions, gaps, fractions, args):
    """The study's archive: dims record, mass_offset_ratio, angle, gap, barrier (and point for the
    pads' and corners' forces), the code's D_M and D_TM per eccentricity, the suite."""
    from engine.results import PEAKS, PLAN_PEAKS, TORSION_PEAKS
    from pipeline.archive import labelled_dataset, variable
    from pipeline.assess.derived import bumper_stress, crushed, largest_floor_accel
    from pipeline.assess.validity import RUBBER_STRESS_LIMIT, bumper_stress_exceeds
    from pipeline.suite_labels import archive_variables

    n_r, n_e, n_a, n_g = len(suite.pairs), eccs.size, thetas.size, len(gaps)
    per_angle = 1 + 2 * n_g

    def blocks(name):
        """(record, mass_offset_ratio, angle, member of the angle) values of the sweep."""
        values = swept[name].values
        return values.reshape(n_r, n_e, n_a, per_angle, *values.shape[2:])

    dims_free = ("record", "mass_offset_ratio", "angle")
    dims_wall = ("record", "mass_offset_ratio", "angle", "gap", "barrier")
    data = {}
    declared = {q.name: q for q in (*PEAKS, *PLAN_PEAKS, *TORSION_PEAKS)}
    for name in PER_RUN:
        q = declared[name]
        stack = blocks(name)
        if name == "peak_total_accel":  # the largest over the floors
            stack = largest_floor_accel(stack)
        free = stack[:, :, :, 0]
        walls = stack[:, :, :, 1:].reshape(n_r, n_e, n_a, n_g, 2)
        what = "the largest over the floors" if name == "peak_total_accel" else ""
        data[f"free_{name}"] = variable(dims_free, free, q.units,
                                        f"{q.long_name}, without wall {what}".strip())
        data[name] = variable(dims_wall, walls, q.units, f"{q.long_name} {what}".strip())
    for name in ("max_point_force", "max_point_indentation", "max_impact_force_wall"):
        q = declared[name]
        stack = blocks(name)[:, :, :, 1:]
        stack = stack.reshape(n_r, n_e, n_a, n_g, 2, stack.shape[-1])
        along = "point" if "point" in name else "wall"
        data[name] = variable((*dims_wall, along), stack, q.units, q.long_name)
    pads = data["max_point_force"].values[..., 1, :]  # (record, ecc, angle, gap, point)
    pad_crushed = crushed(data["max_point_indentation"].values[..., 1, :], DELTA_U)
    # a crushed pad's largest force is the slab bearing on the wall behind it, not a stress
    # in its rubber: its stress is left out (NaN), its crushing flagged on its own
    stress = np.where(pad_crushed, np.nan, bumper_stress(pads, 1, AREA))
    data["pad_stress"] = variable((*dims_wall[:-1], "point"), stress, "Pa",
                                  "mean contact stress in each pad's rubber at its largest "
                                  "force (NaN where the pad is crushed: the slab bears on the "
                                  "wall behind it)")
    data["pad_crushed"] = variable(
        (*dims_wall[:-1], "point"), pad_crushed.astype(np.int8), "1",
        "1 where the pad is crushed beyond delta_u (its rubber's ultimate strain)")
    data["invalid_pad_stress"] = variable(
        dims_wall[:-1], bumper_stress_exceeds(np.nan_to_num(stress)).any(axis=-1)
        .astype(np.int8), "1", "1 where an uncrushed pad's stress passes the rubber tests' "
        f"largest, {RUBBER_STRESS_LIMIT / 1e6:.3g} MPa (pipeline.assess.validity): outside "
        "the law's range, flagged and counted in every summary, kept in its statistics")
    first = swept
    coords = {
        "mass_offset_ratio": variable("mass_offset_ratio", eccs, "1", "the mass centre's offset "
                                      "from the plan's centre as a fraction of each plan "
                                      "dimension (e_x = e b_x, e_y = e b_y)"),
        "angle": variable("angle", thetas, "degree", "incidence angle: the pair rotated "
                          "counterclockwise"),
        "gap": variable("gap", np.array(gaps), "1", "the clear gap: a fraction of the code's "
                        "D_M, or its D_TM at the eccentricity (ASCE 7-22 17.5.3.3)"),
        "barrier": variable("barrier", np.array(BARRIERS), "1", "the moat's barrier"),
        "point": first["point"], "point_wall": first["point_wall"],
        "point_along": first["point_along"], "wall": first["wall"],
        "record": first["record"], "direction": first["direction"],
    }
    data["D_TM"] = variable("mass_offset_ratio", [c["d_tm"] for c in code], "m",
                            "the code's total maximum displacement D_TM (ASCE 7-22 17.5.3.3, "
                            "the actual eccentricity plus the accidental 5%, >= 1.15 D_M)")
    data["gap_length"] = variable(("mass_offset_ratio", "gap"),
                                  [[*(f * suite.design.d_m for f in fractions), c["d_tm"]]
                                   for c in code], "m",
                                  "the moat's clear gap from the slab's edges")
    suite_data, suite_coords, suite_attrs = archive_variables(suite)
    attrs = {**suite_attrs, "plan_size_m": json.dumps(list(map(float, args.plan_m))),
             "pads_per_wall": int(args.pads), "pad_thickness_m": THICKNESS,
             "pad_positions_m": json.dumps([list(map(float, p)) for p in positions]),
             "paper_pads_per_wall": N_BUMPERS,
             "bearings": f"a {DEFAULT_GRID[0]} x {DEFAULT_GRID[1]} grid under the slab, the "
                         f"outer ones at its edges, each 1/{DEFAULT_GRID[0] * DEFAULT_GRID[1]} "
                         "of the isolator (engine.torsion)"}
    return labelled_dataset({**data, **suite_data}, {**coords, **suite_coords}, attrs)


def orbit_variables(suite, building, ecc, args, engine) -> dict:
    """The orbits the figure draws: the first pair at angle 0 and the largest eccentricity,
    without wall: the centre's and the corners' (engine.torsion.corner_orbits)."""
    from engine.torsion import CORNERS, corner_orbits, shifted
    from pipeline.archive import variable

    pair = suite.pairs[0]
    plan = building.torsion.plan_size
    run = engine.simulate(pair.accel, pair.dt, engine.Contact.none(1), shifted(building, ecc),
                          engine.DEFAULT_DT if args.dt is None else args.dt,
                          history=engine.History([0], every=ORBIT_EVERY),
                          scale=[suite.factors[0]])
    hist = run.history
    centre = hist["floor_disp"][0, :, 0]
    corners = corner_orbits(centre[:, None, :], hist["floor_rotation"][0, :, :1],
                            np.array(CORNERS) * np.array(plan) / 2)
    return {"orbit_time": variable("orbit_time", hist["time"], "s", "time"),
            "orbit_centre": variable(("orbit_time", "direction"), centre, "m",
                                     "the plan centre's orbit (first pair, angle 0, the "
                                     "largest eccentricity, no wall)"),
            "orbit_corners": variable(("orbit_time", "corner", "direction"), corners, "m",
                                      "the corners' orbits (CORNERS order: +x+y, -x+y, -x-y, "
                                      "+x-y)")}


recipe = Recipe(
    name="torsion", figure="beyond the paper",
    summary="The slab twists: an eccentric mass on bearings where they stand, the corners "
            "against the code's D_TM, and the force on each bumper",
    compute=compute, plot=plot, check=check,
    chosen=(f"a {PLAN[0]:g} x {PLAN[1]:g} m slab on a 4 x 4 grid of bearings; eccentricity "
            f"{', '.join(f'{e:g}' for e in ECCENTRICITIES)} of each plan dimension; the 22 "
            "FEMA P695 far-field pairs at the MCE_R, angles 0-165 every 15; gaps "
            f"{', '.join(f'{f:g}' for f in GAP_FRACTIONS)} D_M and D_TM; {PADS} pads per "
            f"wall; quick: {QUICK_PAIRS} pairs, angles 0, 45, 90, eccentricity "
            f"{', '.join(f'{e:g}' for e in QUICK_ECCENTRICITIES)}, gaps "
            f"{', '.join(f'{f:g}' for f in QUICK_GAP_FRACTIONS)} D_M and D_TM"),
    records=(), options=options)
main = recipe.main
