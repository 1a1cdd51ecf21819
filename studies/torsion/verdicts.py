"""studies.torsion's verdicts: the code's allowance for torsion (ASCE 7-22 17.5.3.3) and the
issue's claim that a twisting slab loads one bumper, each with its quantifier, counted by the
one rule (pipeline.assess.outcomes.count: a pair weighs its earthquake's share once, its
cases its angles and eccentricities; ties and runs without contact outside the denominator,
reported beside)."""
from __future__ import annotations

import numpy as np

from pipeline.assess.outcomes import QUANTILES, TOLERANCE, count, weighted_quantiles

from ..common.recipe import Verdict

CLAUSE = "ASCE 7-22 17.5.3.3"


def corner_ratio(ds) -> np.ndarray:
    """(record, mass_offset_ratio, angle): the worst corner's peak over the centre's, no wall."""
    return (ds.free_peak_corner_disp / ds.free_peak_isolator_disp).values


def code_ratio(ds) -> np.ndarray:
    """(mass_offset_ratio,): the code's D_TM / D_M."""
    return ds.D_TM.values / float(ds.attrs["D_M"])


def pad_share(ds, barrier: str = "bumpers") -> np.ndarray:
    """(record, mass_offset_ratio, angle, gap): the worst point's peak force over its wall's peak
    total, on the wall whose total is the largest (NaN without contact): 1 / points when the
    wall's points share its force equally, 1 when one takes it all. A run with a pad past the
    rubber's range (`invalid`) keeps its share: flagged and counted beside, never dropped."""
    sel = ds.sel(barrier=barrier)
    walls = sel.max_impact_force_wall.values  # (..., wall)
    points = sel.max_point_force.values  # (..., point)
    wall_of = np.array([list(ds.wall.values).index(w) for w in ds.point_wall.values])
    worst_wall = np.argmax(walls, axis=-1)
    on = wall_of[None, None, None, None, :] == worst_wall[..., None]
    largest = np.where(on, points, 0.0).max(axis=-1)
    total = np.take_along_axis(walls, worst_wall[..., None], axis=-1)[..., 0]
    return np.where(total > 0, largest / np.where(total > 0, total, 1.0), np.nan)


def invalid(ds, barrier: str) -> np.ndarray:
    """(record, mass_offset_ratio, angle, gap) bool: an uncrushed pad past the rubber's tested
    stress (invalid_pad_stress; never for the bare wall)."""
    flags = ds.invalid_pad_stress.values.astype(bool)
    return flags if barrier == "bumpers" else np.zeros(flags.shape, bool)


def points_per_wall(ds, barrier: str) -> int:
    """The contact points on a wall: the pads, or the bare wall's two corners."""
    return int(ds.attrs["pads_per_wall"]) if barrier == "bumpers" else 2


def spread(values, weights) -> dict:
    """The weighted 16th, 50th and 84th percentiles of values (record, ...) over the pairs and
    the rest (each pair's weight shared by its cases), NaN cases left out."""
    values = np.asarray(values, float)
    cases = values.reshape(values.shape[0], -1)
    w = np.repeat(np.asarray(weights, float)[:, None] / cases.shape[1], cases.shape[1], axis=1)
    keep = np.isfinite(cases)
    if not keep.any():
        return {"p16": None, "median": None, "p84": None, "cases": 0}
    q = weighted_quantiles(cases[keep], w[keep], QUANTILES)
    return {"p16": float(q[0]), "median": float(q[1]), "p84": float(q[2]),
            "cases": int(keep.sum())}


def check(ds) -> list[Verdict]:
    weights = ds.record_weight.values
    events = ds.record_event.values
    ratio = corner_ratio(ds)
    allowed = code_ratio(ds)[None, :, None]
    eccs = ds.mass_offset_ratio.values
    out = []

    held = count("most", ratio <= allowed, np.ones(ratio.shape, bool), weights=weights,
                 events=events)
    stats = {f"{e:g}": spread(ratio[:, i], weights) for i, e in enumerate(eccs)}
    out.append(Verdict(
        CLAUSE, "the code's torsion allowance covers the corners' extra travel: the worst "
        "corner's peak over the centre's within D_TM / D_M, on most pairs, angles and "
        "eccentricities at the MCE_R",
        f"corner / centre (median, 84th) {_by_ecc(stats, eccs)} against D_TM / D_M "
        f"{', '.join(f'{r:.3g}' for r in code_ratio(ds))}; {held.text('runs')}",
        held.verdict, {"corner_over_centre": stats, "code_ratio": code_ratio(ds).tolist(),
                       **held.numbers()}))

    corner = ds.free_peak_corner_disp.values
    within = corner <= ds.D_TM.values[None, :, None]
    held = count("most", within, np.ones(within.shape, bool), weights=weights, events=events)
    shares = {f"{e:g}": float(np.average((~within[:, i]).mean(axis=-1), weights=weights))
              for i, e in enumerate(eccs)}
    out.append(Verdict(
        CLAUSE, "the moat's clearance D_TM is not exceeded by the slab's worst corner without "
        "wall on most pairs and angles at the MCE_R",
        "the worst corner passes D_TM in a weighted share "
        f"{', '.join(f'{v:.0%} (e {k})' for k, v in shares.items())} of the runs; "
        f"{held.text('runs')}", held.verdict, {"share_exceeding_D_TM": shares,
                                               **held.numbers()}))

    for barrier in ("bumpers", "bare wall"):
        share = pad_share(ds, barrier)
        n = points_per_wall(ds, barrier)
        equal = 1.0 / n
        apart = invalid(ds, barrier)
        contact = np.isfinite(share)
        changed = np.abs(share - equal) > TOLERANCE * equal
        held = count("most", share > equal, contact, changed=changed, weights=weights,
                     events=events)
        stats = {f"{g}": spread(share[..., j], weights)
                 for j, g in enumerate(ds.gap.values)}
        what = f"of its {n} pads" if barrier == "bumpers" else "of its two corners"
        out.append(Verdict(
            "design", f"a twisting slab puts its wall's force on one point ({barrier}): the "
            f"worst {what} carries more than its equal share 1/{n} of the wall's peak, on "
            "most pairs and angles with contact",
            f"the worst point's share of its wall's peak (median, 84th) "
            f"{_by_gap(stats)}; {held.text('runs')}; of the runs with contact, "
            f"{int((apart & contact).sum())} flagged (an uncrushed pad past the rubber's tested "
            "stress), kept in the share", held.verdict,
            {"share": stats, "equal_share": equal, "invalid_runs": int(apart.sum()),
             "invalid_runs_with_contact": int((apart & contact).sum()), **held.numbers()}))
    return out


def _by_ecc(stats, eccs) -> str:
    return ", ".join(f"{s['median']:.3g}, {s['p84']:.3g} (e {e:g})"
                     for e, s in zip(eccs, stats.values(), strict=True))


def _by_gap(stats) -> str:
    return ", ".join(f"{s['median']:.2f}, {s['p84']:.2f} at {g}" if s["median"] is not None
                     else f"no contact at {g}" for g, s in stats.items())
