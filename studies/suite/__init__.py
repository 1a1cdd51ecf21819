"""Beyond the paper: do bumpers help across code-scaled record pairs, and do the paper's
conclusions hold as the paper words them?

The paper draws its conclusions from four records. This recipe runs the paper's building in
plan (coupled isolators, a square moat by default: --moat) under the FEMA P695 far-field record
pairs, scaled to a site's MCE_R spectrum by a code's rule (pipeline.motions.code_suite: ASCE 7-22
chapter 17 by default, --rule p695 or the labelled "displacement" option), at three intensity
levels (the service level, a third of the MCE_R; the design earthquake, two thirds; the MCE_R).
The moat's clear gap is a fraction of the code's D_M (0.4 to 1.2, GAPS) and the code's
minimum clearance D_TM. At each gap the paper's bumpers (5 cm, Fig. 19's 4, 8, 16, 32 per side
against each of Fig. 21's three wall stiffnesses) are compared with the bare wall at the same
gap (the paper's linear law); the building without wall runs once per pair and level. Every pair
runs every level and configuration in one batched engine call (per-member scale factors).

Counting (pipeline.assess.outcomes, SPEC section 6): with bumpers against the bare wall, each
(pair, level, gap) point is HELPED (amplification with / without below 1 - 2%), NEUTRAL (within
2%, exact ties included) or HURT (above 1 + 2%), and counted only where contact occurs in at
least one of the two configurations; elsewhere the two runs are the same unconstrained run and
the point is "no contact", never a tie or harm. Pairs are weighted per earthquake
(record_weight: 1 / the pairs of the same earthquake, normalised to sum to the number of
pairs), in every share, quantile and verdict.

Validity (pipeline.assess.validity): every run is checked against the model's range (the bumpers'
contact stress against the rubber's 30.9 MPa, the largest floor acceleration against 5 g, a
linear story's shear against the code's superstructure capacity, the wall's force against a
capacity if given); the flags are stored per run (`invalid_*`, `bare_invalid_*`,
`free_invalid_*`), and how each run ended beside its collapse flag (`collapse_mode`, a CF flag
variable: a story's drift, the isolator's capacity, a numerical instability; 0 where it stood),
every count of collapses counting each mode. Runs outside the range are kept in the helped /
neutral / hurt shares, the amplification quantiles and the verdicts, with their number stated:
the share of each cell's pairs with a run outside (`counted_outside_range`) and, in every
verdict, the runs outside and the verdict's fraction without them. Leaving them out of the
statistics instead would keep the mild cases only (a pounding hard enough to matter is the one
that leaves the range), and bias every median towards the bumpers' harm.

Verdicts: each of the paper's conclusions with its quantifier as the paper wrote it ("for all
examined excitations": every pair; "in most cases": more than half of the counted cases where
the quantity changes by more than the tolerance; "almost all": ALMOST_EVERY of them; "may",
"can": one case at least; a claim without quantifier is read as stated in its text), the
fraction it holds for, and "agrees" only when the quantifier holds. Comparisons are made only
between configurations where something happens (contact, crushing).

The derived responses (the largest floor acceleration and interstory drift, the bumpers'
stress, "crushed") are pipeline.assess.derived's; --moat, --wall-capacity-mn, the default pairs and
the bare wall's description are studies.common.options'; QUANTILES is pipeline.assess.outcomes'.
"""
from __future__ import annotations

import json
from dataclasses import dataclass

import numpy as np

from engine.units import CM
from pipeline.assess import derived
from pipeline.assess.outcomes import (
    ALMOST_EVERY,
    HELPED,
    HURT,
    NEUTRAL,
    QUANTILES,
    amplification,
    effect,
    weighted_quantiles,
    with_collapse,
)
from pipeline.motions.code_suite import LEVELS, describe
from pipeline.suite_labels import archive_variables

from ..common.options import (
    QUICK_PAIRS,
    add_bound,
    add_moat,
    add_stories,
    add_wall_capacity,
    bare_wall_text,
    chosen_pairs,
    scaled_suite,
    site_options,
    wall_capacity,
)
from ..common.paper import AREA, DELTA_U, FIG19_COUNTS, FIG21_WALL_KS, STRAIN, THICKNESS
from ..common.recipe import Recipe, provenance, run_options
from .archive import (
    OUTCOMES,
    PREFIX,
    RESPONSES,
    broadcast_weights,
    contact,
    outside,
    response,
)
from .figure import plot
from .verdicts import check

GAPS = (0.4, 0.5, 0.6, 0.8, 1.0, 1.2)
"""Clear gaps as fractions of D_M (at the bound run, --bound); the code's clearance D_TM is
added among them. The nonlinear building in plan reaches a median 0.84 D_M at the MCE_R
without wall (0.69-1.05 D_M from the 16th to the 84th percentile, the 22 far-field pairs at the
lower bound, `free_peak_isolator_disp`; 0.61 while the studies ran the paper's isolation
dashpot, before issue 38), so that the gaps below D_M are hit by most pairs and those above by
few; 0.4 D_M leaves 7.4 cm in front of the 5 cm bumpers at the lower bound (D_M
31.0 cm, lambda_min 0.8), 5.5 cm at nominal properties (D_M 26.2 cm)."""
QUICK_GAPS = (0.4, 0.6)
QUICK_LEVELS = ("design", "MCE_R")
QUICK_COUNTS = (4, 32)
PEAKS = ("peak_isolator_disp", "peak_total_accel", "peak_interstory_drift", "max_impact_force",
         "max_indentation", "n_impacts")
"""The engine's peaks the archive keeps for every run (plan: resultants)."""


def options(p) -> None:
    site_options(p)
    add_bound(p)
    add_stories(p)
    add_moat(p)
    add_wall_capacity(p)


@dataclass(frozen=True)
class Grid:
    """What every pair runs. level_names (L,) and levels (L,): fractions of the MCE_R;
    fractions (G,) of D_M, ascending, and gaps (G,) m; code_gap: the index of the code's
    clearance D_TM among them (None: not in the grid); counts (N,) bumpers per side; wall_ks
    (K,) N/m."""

    level_names: tuple
    levels: np.ndarray
    fractions: np.ndarray
    gaps: np.ndarray
    code_gap: int | None
    counts: tuple
    wall_ks: tuple

    @property
    def block(self) -> int:
        """Members per level: no wall, the bare wall per gap, the bumpers per (gap, n, k_w)."""
        return 1 + self.gaps.size * (1 + len(self.counts) * len(self.wall_ks))

    def members(self):
        """One level's engine.Contact, in the order of `block`."""
        import engine

        g, n, k = np.meshgrid(self.gaps, np.array(self.counts), np.array(self.wall_ks),
                              indexing="ij")
        return engine.Contact.concat([
            engine.Contact.none(1), engine.Contact.linear(self.gaps),
            engine.Contact.bumper(g.ravel(), thickness=THICKNESS, n_bumpers=n.ravel(),
                                  k_w=k.ravel())])

    def split(self, values) -> dict:
        """(R, L x block, ...) -> configuration -> free (R, L, ...), bare (R, L, G, ...),
        bumpers (R, L, G, N, K, ...)."""
        values = np.asarray(values)
        r, rest = values.shape[0], values.shape[2:]
        v = values.reshape(r, self.levels.size, self.block, *rest)
        n_g = self.gaps.size
        return {"free": v[:, :, 0], "bare": v[:, :, 1:1 + n_g],
                "bumpers": v[:, :, 1 + n_g:].reshape(r, self.levels.size, n_g,
                                                     len(self.counts), len(self.wall_ks), *rest)}


def make_grid(design, quick: bool) -> Grid:
    """The grid for the code's design (pipeline.motions.target.IsolationDesign): the gaps GAPS x D_M
    and D_TM (which marks an existing fraction if it coincides with one)."""
    names = QUICK_LEVELS if quick else tuple(LEVELS)
    fractions = np.array(QUICK_GAPS if quick else GAPS, dtype=float)
    code = design.d_tm / design.d_m
    if not np.any(np.isclose(fractions, code)):
        fractions = np.sort(np.append(fractions, code))
    return Grid(names, np.array([LEVELS[n] for n in names]), fractions,
                fractions * design.d_m, int(np.argmin(abs(fractions - code))),
                QUICK_COUNTS if quick else FIG19_COUNTS, tuple(FIG21_WALL_KS))


def compute(args):
    from pipeline.assess.validity import Limits, code_story_capacity

    pairs, names = chosen_pairs(args, QUICK_PAIRS)
    suite = scaled_suite(args, pairs, names)  # at --bound: its building, its D_M and D_TM
    grid = make_grid(suite.design, args.quick)
    peaks, swept = run(suite, grid, args)
    # the superstructure's strength from the code's largest base shear over the bounds
    limits = Limits(story_shear=code_story_capacity(suite.basis.force_design, suite.building),
                    wall_force=wall_capacity(args))
    ds = assemble(grid, peaks, suite.names, suite.weights, suite.building, limits)
    data, coords, attrs = archive_variables(suite)
    attrs.update(moat=args.moat, suite=describe(suite))
    return ds.assign_coords(coords).assign(data).assign_attrs({**provenance(swept), **attrs})


def run(suite, grid: Grid, args):
    """Every pair at every level and configuration, on the pipeline's executor
    (pipeline.sweep: resumable from the recipe's work folder, in this process or on dask with
    --workers N >= 2 or --scheduler): the bumpers over (gap, n_bumpers, wall_k), the bare wall
    per gap and the building without wall, each at every level, a pair's members scaled by its
    MCE_R factor x the level; the building at the suite's bound (suite.building). Returns
    (configuration -> peak name -> array, see Grid.split; the sweep's Dataset, whose
    provenance the archive keeps)."""
    import pipeline

    ds = pipeline.sweep(suite.pairs, moat=args.moat, gap=grid.gaps, thickness=THICKNESS,
                        n_bumpers=list(grid.counts), wall_k=list(grid.wall_ks),
                        baseline=True, unconstrained=True, level=grid.levels,
                        factors=suite.factors,
                        **{**run_options(args), "building": suite.building})
    blocks = {"free": "unconstrained_", "bare": "baseline_", "bumpers": ""}
    return {config: {name: ds[prefix + name].values
                     for name in PEAKS + ("collapsed", "collapse_mode") if prefix + name in ds}
            for config, prefix in blocks.items()}, ds


# --- The archive: peaks, validity flags and statistics, from peaks (also hand-made ones). ---

DIMS = {"free": ("record", "level"), "bare": ("record", "level", "gap_fraction"),
        "bumpers": ("record", "level", "gap_fraction", "n_bumpers", "wall_k")}


def config_text() -> dict[str, str]:
    """Configuration -> how the archive's long names say it."""
    return {"free": "without wall",
            "bare": f"against the bare wall at the same gap ({bare_wall_text()})",
            "bumpers": "with the bumpers"}


def assemble(grid: Grid, peaks: dict, names, weights, building, limits):
    """The archive from the peaks: configuration (free, bare, bumpers) -> PEAKS name -> array
    shaped as Grid.split gives (SI: m, m/s^2 over the building's levels, m over its stories, N,
    m, impacts), and where the building can collapse collapsed and collapse_mode (its runs'
    codes, engine.results.COLLAPSE_MODES); names (R,) of the pairs; weights (R,) per
    earthquake; building: the engine.Building run; limits: pipeline.assess.validity.Limits.
    Adds the validity flags, how each run ended (collapse_mode: 0 where it stood, every run
    of a building that cannot collapse), the bumpers' contact stress and the statistics
    (add_statistics)."""
    from engine.results import quantity
    from pipeline.archive import COLLAPSE_MODE, collapse_mode_variable, labelled_dataset, variable
    from pipeline.assess.collapse_modes import collapse_numbers
    from pipeline.assess.validity import FLAGS, flags_of, shape_factor

    data, said = {}, config_text()
    counts = np.array(grid.counts, float)[:, None]  # (N, 1): against the wall_k axis
    for config, prefix in PREFIX.items():
        along = {"peak_total_accel": ("floor",), "peak_interstory_drift": ("story",)}
        for name in PEAKS:
            q = quantity(name)
            data[prefix + name] = variable(DIMS[config] + along.get(name, ()),
                                           peaks[config][name], q.units,
                                           f"{q.long_name} {said[config]} (resultant)")
        flagged = flags_of(peaks[config], building, limits, area=AREA, thickness=THICKNESS,
                           n_bumpers=counts if config == "bumpers" else None)
        for name, value in flagged.items():
            data[prefix + name] = variable(DIMS[config], value.astype(np.int8), "1",
                                           f"1 where {FLAGS[name]} ({said[config]})")
        mode = peaks[config]["collapse_mode"] if "collapsed" in peaks[config] \
            else np.zeros(flagged["invalid_collapse"].shape, np.int8)
        data[prefix + "collapse_mode"] = collapse_mode_variable(
            DIMS[config], mode, f"{COLLAPSE_MODE.long_name} ({said[config]})")
    stress = derived.quantity("bumper_stress")
    data["bumper_stress"] = variable(
        DIMS["bumpers"], stress(peaks["bumpers"], n_bumpers=counts, area=AREA), stress.units,
        stress.describe(each=f"each bumper ({AREA * 1e6:g} mm2)"))
    data["record_weight"] = variable("record", np.asarray(weights, float), "1",
                                     "the pair's weight: 1 / the pairs of the same earthquake, "
                                     "normalised to sum to the number of pairs")
    coords = {
        "record": variable("record", np.array(names), "1", "record pair"),
        "level": variable("level", np.array(grid.level_names), "1", "intensity level"),
        "level_factor": variable("level", grid.levels, "1", "the level as a fraction of the "
                                 "MCE_R: every pair's MCE_R factor times this"),
        "gap_fraction": variable("gap_fraction", grid.fractions, "1", "seismic gap / D_M"),
        "gap": variable("gap_fraction", grid.gaps, "m", "seismic gap (clear, before bumpers)"),
        "code_clearance": variable("gap_fraction", (np.arange(grid.fractions.size)
                                                    == grid.code_gap).astype(np.int8), "1",
                                   "1 at the code's minimum clearance D_TM"),
        "n_bumpers": variable("n_bumpers", np.array(grid.counts), "1",
                              f"bumpers of {THICKNESS / CM:g} cm on each side"),
        "wall_k": variable("wall_k", np.array(grid.wall_ks), "N m-1",
                           "moat-wall stiffness behind the bumpers"),
        "floor": variable("floor", np.arange(building.n_levels), "1", "level: 0 the base"),
        "story": variable("story", np.arange(1, building.n_stories + 1), "1", "story"),
    }
    counts = {prefix + name: int(np.sum(data[prefix + name].values))
              for prefix in PREFIX.values() for name in FLAGS}
    ds = labelled_dataset(data, coords, {
        "validity_limits": limits.describe(), "invalid_counts": json.dumps(counts),
        "collapse_modes": json.dumps({prefix + "collapse_mode": collapse_numbers(
            data[prefix + "collapse_mode"].values) for prefix in PREFIX.values()}),
        "runs": int(sum(np.prod(peaks[c]["n_impacts"].shape) for c in PREFIX)),
        "bumper_shape_factor": float(shape_factor(AREA, THICKNESS)),
        "bumper_crush_limit": DELTA_U, "story_capacity": limits.story_shear or "none",
        "statistics": STATISTICS_TEXT})
    ds["bumper_shape_factor"] = ((), float(shape_factor(AREA, THICKNESS)), {
        "units": "1", "long_name": "the bumpers' shape factor: loaded area / area free to "
        "bulge (side / (4 t))"})
    return add_statistics(ds)


STATISTICS_TEXT = (
    "with bumpers against the bare wall at the same gap: helped (amplification below 1 - 2%), "
    "neutral (within 2%, ties included), hurt (above 1 + 2%), pipeline.assess.outcomes; "
    "counted only where contact occurs with the bumpers or the bare wall, else no_contact; "
    "pairs weighted per earthquake (record_weight); runs outside the model's range (invalid_*) "
    "kept in the shares, quantiles and verdicts, their number stated (counted_outside_range, "
    "and in each verdict with its fraction without them)")


def _with_without(ds, name: str) -> tuple[np.ndarray, np.ndarray]:
    """The response `name` with the bumpers and against the bare wall at the same gap, both
    as arrays over DIMS["bumpers"]."""
    dims = DIMS["bumpers"]
    a = response(ds, name)
    return (a.transpose(*dims).values,
            response(ds, name, "bare").broadcast_like(a).transpose(*dims).values)


def add_statistics(ds):
    """Amplifications, effects, the weighted shares of helped / neutral / hurt / no contact,
    the weighted quantiles of the amplification over the pairs with contact, the share of
    those with a run outside the model's range, and the share
    of pairs whose bumpers are crushed."""
    from pipeline.archive import variable

    names = list(RESPONSES)
    dims = DIMS["bumpers"]
    pairs = [_with_without(ds, r) for r in names]
    # A collapse is a collapse, never a large amplification: where a run collapsed the
    # effect is the collapse's (with_collapse) and the amplification is not a number.
    fell = ds["invalid_collapse"].transpose(*dims).values.astype(bool)
    fell_bare = ds["bare_invalid_collapse"].broadcast_like(ds["invalid_collapse"]) \
        .transpose(*dims).values.astype(bool)
    either = fell | fell_bare
    amp = np.stack([np.where(either, np.nan, amplification(a, b)) for a, b in pairs])
    eff = np.stack([with_collapse(effect(a, b), fell, fell_bare) for a, b in pairs])
    touch = contact(ds).transpose(*dims).values
    valid = ~(outside(ds, "bumpers") | outside(ds, "bare")).transpose(*dims).values
    w = ds.record_weight.values
    out = ds.assign_coords(
        response=variable("response", np.array(names), "1",
                          "; ".join(f"{k}: {v}" for k, v in RESPONSES.items())),
        outcome=variable("outcome", np.array(OUTCOMES), "1", "helped / neutral / hurt within "
                         "the tolerance where contact occurs, else no_contact"),
        quantile=variable("quantile", np.array(QUANTILES), "1", "quantile over the pairs"))
    out["amplification"] = variable(("response", *dims), amp, "1",
                                    "peak with bumpers / against the bare wall at the same gap")
    out["contact"] = variable(dims, touch.astype(np.int8), "1", "1 where the bumpers or the "
                              "bare wall at the same gap are hit")
    out["effect"] = variable(("response", *dims), np.where(touch, eff, 0).astype(np.int8), "1",
                             "-1 helped, 0 neutral or no contact (see contact), 1 hurt")
    out["outcome_share"] = variable(
        ("response", "outcome", *dims[1:]), _shares(eff, touch, w), "1",
        "weighted share of the pairs (record_weight) helped, neutral, hurt, or with no contact")
    out["amplification_quantile"] = variable(
        ("response", "quantile", *dims[1:]), _quantiles(amp, touch & ~either, w), "1",
        "weighted 16th, 50th, 84th percentiles of the amplification over the pairs with "
        "contact and no collapse, runs outside the model's range included (see "
        "counted_outside_range; NaN: no contact)")
    out["quantile_pairs"] = variable(dims[1:], (touch & ~either).sum(axis=0), "1",
                                     "pairs behind amplification_quantile")
    out["collapse_share"] = variable(
        ("configuration", *dims[1:]), np.stack([
            _weighted_mean(fell, np.ones_like(fell), w),
            _weighted_mean(fell_bare, np.ones_like(fell), w)]), "1",
        "weighted share of the pairs whose run collapsed, with the bumpers and against the "
        "bare wall (counted as the collapse's effect in outcome_share: hurt where only the "
        "bumpers' run collapsed, helped where only the bare wall's, neutral where both)")
    out = out.assign_coords(configuration=variable(
        "configuration", np.array(["bumpers", "bare"]), "1", "with the bumpers, or against "
        "the bare wall at the same gap"))
    out["counted_outside_range"] = variable(
        dims[1:], _weighted_mean(~valid, touch, w), "1", "weighted share of the pairs with "
        "contact whose bumper or bare-wall run is outside the model's range (NaN: none)")
    crushed = derived.crushed(ds.max_indentation.transpose(*dims).values, DELTA_U)
    out["fraction_crushed"] = variable(
        dims[1:], _weighted_mean(crushed, np.ones_like(crushed), w), "1",
        f"weighted share of the pairs whose bumpers are crushed beyond {DELTA_U / CM:g} cm")
    return out


def _weighted_mean(values, counted, w) -> np.ndarray:
    """Over axis 0 (records): the weighted share of `values` among the `counted`, NaN where
    nothing is counted."""
    ww = broadcast_weights(w, values.shape) * counted
    total = ww.sum(axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(total > 0, (ww * values).sum(axis=0) / total, np.nan)


def _shares(eff, touch, w) -> np.ndarray:
    """(response, outcome, ...) weighted shares of all pairs in each outcome (sum 1)."""
    ww = broadcast_weights(w, touch.shape)
    total = ww.sum(axis=0)
    out = []
    for e in eff:
        parts = [(ww * (touch & (e == k))).sum(axis=0) for k in (HELPED, NEUTRAL, HURT)]
        out.append(np.stack([*parts, (ww * ~touch).sum(axis=0)]) / total)
    return np.stack(out)


def _quantiles(amp, keep, w) -> np.ndarray:
    """(response, quantile, ...) weighted quantiles over the records (axis 1 of amp) at the
    points kept (records x cells)."""
    n_resp = amp.shape[0]
    cells = amp.shape[2:]
    out = np.full((n_resp, len(QUANTILES), *cells), np.nan)
    for r in range(n_resp):
        for cell in np.ndindex(*cells):
            k = keep[(slice(None), *cell)]
            out[(r, slice(None), *cell)] = weighted_quantiles(
                amp[(r, slice(None), *cell)][k], np.asarray(w)[k], QUANTILES)
    return out


recipe = Recipe(
    name="suite", figure="beyond the paper",
    summary="Do bumpers help across code-scaled record pairs? The FEMA P695 far-field pairs "
            "scaled to a site's MCE_R (ASCE 7-22 ch. 17), in plan, at the service, design and "
            "MCE_R levels, gaps at fractions of D_M and D_TM, 4-32 bumpers and three wall "
            "stiffnesses against the bare wall; the paper's conclusions with their quantifiers",
    compute=compute, plot=plot, check=check, records=(), options=options,
    chosen=(f"site S_MS 1.5 g, S_M1 0.9 g, T_L 8 s; levels service 1/3, design 2/3, MCE_R; "
            f"gaps {', '.join(map(str, GAPS))} D_M and D_TM; {THICKNESS / CM:g} cm bumpers, "
            f"strain {STRAIN:g}, no cavity; tolerance 2%; pairs "
            f"weighted per earthquake; 'almost all' = {ALMOST_EVERY:.0%} of the cases that change; "
            f"quick: {QUICK_PAIRS} pairs, levels {', '.join(QUICK_LEVELS)}, gaps "
            f"{', '.join(map(str, QUICK_GAPS))} D_M and D_TM, {QUICK_COUNTS[0]} and "
            f"{QUICK_COUNTS[1]} bumpers"),
)
main = recipe.main
