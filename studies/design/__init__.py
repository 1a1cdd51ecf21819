"""Beyond the paper: what bumpers to install for a building and a gap short of the code's.

The record pairs (default: the 22 FEMA P695 far-field pairs, as recorded) are scaled to the
site's MCE_R by a code's rule (pipeline.motions.code_suite: ASCE 7-22 chapter 17 by default)
and run in plan (a rectangular moat by default) at three intensity levels, the service, design
and MCE_R levels of pipeline.motions.code_suite.LEVELS (1/3, 2/3 and 1 x the MCE_R factors).
The gap is the user's
(--gap-cm, or --gap-dm as a fraction of the code's D_M); by default 0.8 D_M, short of the
code's clearance D_TM: where bumpers matter.

A candidate is a bumper layout: thickness t, cavity depth as a ratio c/t (paper 5.3), count per
wall n, shape factor S (a square pad of side 4 S t: the plan size follows from S and t) and
wall stiffness k_w. Each is judged at every level on every pair, with the validity flags of
pipeline.assess.validity per member (contact stress against the rubber's limit, floor acceleration,
story shear against the code's capacity when the stories are linear, wall force if a capacity
is given), and the statistics weighted per earthquake (pipeline.motions.code_suite: no event
dominates).

Objective (--objective): the weighted 84th percentile (default) or median over the pairs of the
largest peak floor acceleration at the MCE_R (the other one breaks ties). The 84th percentile by
default: at a gap short of D_TM but near D_M about half the pairs reach the wall at the MCE_R,
and the median pair, which does not, cannot tell one layout from another. Constraints, each a
command-line option:
- within limits (--within-limits, default 0.84): under at least this weighted fraction of the
  pairs at the MCE_R the bumpers stay uncrushed and their contact stress within the rubber's
  limit (pipeline.assess.validity.RUBBER_STRESS_LIMIT, 30.9 MPa; --no-stress-limit: uncrushed only,
  the old criterion);
- service (--service-contact, default 0): at most this weighted fraction of the pairs touches
  the bumpers at the service level;
- design (--hurt-design, default 1: not constrained): at most this weighted fraction of the
  pairs is hurt at the design level by the bumpers against the bare wall at the same gap
  (pipeline.assess.outcomes, 2% tolerance);
- valid (--valid, default 0: not constrained): at least this weighted fraction of the pairs at
  the MCE_R raises no other validity flag (floor acceleration, story shear, wall force).

Search bounds, from physical limits (Bounds; each named where the optimum meets it):
- thickness - cavity <= gap - D_S: the bumpers leave the clearance the code's procedure gives
  at the service level (D_S: pipeline.motions.target.isolation_design at LEVELS["service"] x
  S_M1; 4.8 cm for the paper's building at the default site), so that frequent earthquakes do
  not reach them by the code's own estimate (the service constraint checks it on the pairs);
  thickness >= 3 cm (its usable stroke, under 2 cm, is of the order of the gap's tolerances);
- c/t <= 1 - the rubber's usable strain (the least of its crush strain and the strain at the
  stress limit, which depends on the pad's shape: 0.589 at S 1.0, 0.765 at S 0.5, 0.469 at S
  1.5 for the paper's rubber with k = 1): a deeper cavity lets the slab bear on the wall's edge
  before the rubber reaches it (paper 5.3: deep enough to use the rubber, no deeper); so a
  cavity also bounds S from below;
- 0.5 <= S <= 1.5 (--shape-factor): the law's stiffness A K_r / t^n is calibrated on a pad
  of S = 1.0 (Kajita et al., 40 x 40 x 10 mm; the paper's bumper: 0.75). The search runs the
  law with the pad's shape (--shape-k, the bumper law's shape_k: Gent & Lindley's compression
  modulus E (1 + 2 k S^2), k = 1 by default): a pad of S 0.5 is half as stiff as Eq. 11 says,
  one of S 1.5 1.8 times as stiff; beyond the range the correction exceeds a factor of 2 and
  rests on a relation fitted on small strains, and below S 0.5 (side < 2 t) the pad is a
  column that bulges and buckles;
- 2 <= n and 2 n x side <= the wall's length (--wall-length-m, default 18 m: a square slab of
  320 t at a typical 10 kPa floor weight is 17.7 m a side): the bumpers stand at least one
  side apart, free to bulge, one near each end at least;
- 500 <= k_w <= 2500 kN/mm: the paper's range of moat walls (5.5).

Search: a coarse grid within the bounds, then a pattern search around the best (the best
feasible one; if none is feasible, the one closest to feasible): each round runs the best's
neighbours one step up and down in every variable (clipped to the bounds), moves to a better
one (and doubles the steps again, up to the first ones) or halves the steps, until the finest
steps (a quarter of the first) find nothing better. Every evaluated candidate is kept
(dimension `candidate`) with its per-pair peaks and flags, how each run ended
(`collapse_mode`), and its statistics per level (the collapses counted by mode).
The optimum is reported as interior (evaluated neighbours on both sides in every variable, with
the constraints its neighbours fail) or at a named bound (physical, or the evaluated grid's edge:
"the optimum may lie beyond"). Beside it, the references at every level: the code's design
(bare wall at D_TM, no bumpers), the bare wall at the gap, and the building without wall.

A member whose clear gap the building without wall never reaches is not run: it is the free run
(engine.simulate is bitwise independent of the batch, and a wall never touched adds exact
zeros), which the tests check against a direct run.
"""
from __future__ import annotations

import functools

import numpy as np

from engine.impact.laws import rubber_bumper
from engine.impact.laws.rubber_bumper import GENT_LINDLEY_K
from engine.units import CM, G
from pipeline.motions.code_suite import LEVELS

from ..common.options import (
    add_bound,
    add_moat,
    add_stories,
    add_wall_capacity,
    checked_gaps,
    chosen_pairs,
    scaled_suite,
    site_options,
    wall_capacity,
)
from ..common.plot import plt
from ..common.recipe import Recipe, provenance, run_options
from .archive import dataset
from .search import (
    Problem,
    Search,
    reference_members,
)
from .space import (
    COARSE,
    MCE,
    OBJECTIVES,
    QUICK,
    QUICK_PAIRS,
    QUICK_ROUNDS,
    REFERENCES,
    ROUNDS,
    SHAPE_FACTOR,
    THICKNESS_MIN,
    WALL_LENGTH,
    WITHIN_LIMITS,
    Bounds,
    criteria,
    grid,
    usable_strain,
)
from .verdicts import check, objective_statistic

GAP_FRACTION = 0.8
"""Default gap / D_M: short of the code's clearance D_TM (1.15 D_M), where bumpers matter."""
SHAPE_K = rubber_bumper.PARAMETERS.shape_k
"""The bumper law's declaration of the rubber's shape factor k (--shape-k)."""


def options(p) -> None:
    site_options(p)
    gap = p.add_mutually_exclusive_group()
    gap.add_argument("--gap-cm", type=float, default=None, metavar="CM",
                     help="the seismic gap to design for, cm (default "
                          f"{GAP_FRACTION:g} D_M)")
    gap.add_argument("--gap-dm", type=float, default=None, metavar="RATIO",
                     help=f"the gap as a ratio to the code's D_M (default {GAP_FRACTION:g})")
    add_moat(p)
    add_bound(p)
    add_stories(p)
    p.add_argument("--objective", choices=tuple(OBJECTIVES), default="p84",
                   help="what is minimised: the weighted 84th percentile (p84, default) or "
                        "median over the pairs of the largest peak floor acceleration at the "
                        "MCE_R")
    p.add_argument("--within-limits", type=float, default=WITHIN_LIMITS, metavar="FRACTION",
                   help="least weighted fraction of the pairs at the MCE_R under which the "
                        "bumpers stay uncrushed and within the stress limit (default "
                        f"{WITHIN_LIMITS:g})")
    p.add_argument("--no-stress-limit", action="store_true",
                   help="uncrushed only, no stress limit (the old criterion; the cavity is "
                        "then bounded by the crush strain)")
    p.add_argument("--stress-limit-mpa", type=float, default=None, metavar="MPA",
                   help="the rubber's contact stress limit, MPa (default 30.9: the largest "
                        "stress of the rubber tests the bumper law is calibrated on)")
    p.add_argument("--service-contact", type=float, default=0.0, metavar="FRACTION",
                   help="largest weighted fraction of the pairs touching the bumpers at the "
                        "service level (default 0: none)")
    p.add_argument("--hurt-design", type=float, default=1.0, metavar="FRACTION",
                   help="largest weighted fraction of the pairs the bumpers hurt at the "
                        "design level against the bare wall at the gap (default 1: not "
                        "constrained)")
    p.add_argument("--valid", type=float, default=0.0, metavar="FRACTION",
                   help="least weighted fraction of the pairs at the MCE_R with no other "
                        "validity flag (floor acceleration, story shear, wall force; default "
                        "0: not constrained, the flags counted only)")
    p.add_argument("--shape-factor", type=float, nargs=2, default=list(SHAPE_FACTOR),
                   metavar=("LO", "HI"), help="the bumpers' shape factor range searched "
                   f"(default {SHAPE_FACTOR[0]:g} {SHAPE_FACTOR[1]:g}: the law's calibration "
                   "within a factor of 2 in stiffness)")
    p.add_argument("--shape-k", type=float, default=GENT_LINDLEY_K, metavar="K",
                   help=f"{SHAPE_K.meaning} (default {GENT_LINDLEY_K:g}: Gent & Lindley's "
                        "unfilled rubber, beta = 2; unverified for the paper's rubber)")
    p.add_argument("--wall-length-m", type=float, default=WALL_LENGTH, metavar="M",
                   help=f"length of each moat wall, m, bounding the count (default "
                        f"{WALL_LENGTH:g})")
    add_wall_capacity(p, "the validity flags")


# ------------------------------------------------------------------------------ compute


def shape_range(args) -> tuple[float, float]:
    """--shape-factor as (lo, hi); SweepError unless 0 < lo <= hi."""
    from pipeline.errors import SweepError

    lo, hi = args.shape_factor
    if not 0 < lo <= hi:
        raise SweepError(f"--shape-factor needs 0 < LO <= HI, got {lo:g} {hi:g}")
    return float(lo), float(hi)


def design_gap(args, design) -> float:
    """The gap (m): --gap-cm, --gap-dm x D_M, or GAP_FRACTION x D_M."""
    from pipeline.errors import SweepError

    if args.gap_cm is not None:
        gap = args.gap_cm * CM
    else:
        gap = (GAP_FRACTION if args.gap_dm is None else args.gap_dm) * design.d_m
    if not gap > 0:
        raise SweepError(f"the gap must be positive, got {gap:g} m")
    return gap if args.gap_cm is not None else float(checked_gaps([gap], design)[0])


def compute(args):
    import engine
    from pipeline.assess import validity
    from pipeline.errors import SweepError
    from pipeline.motions.code_suite import describe as describe_suite
    from pipeline.motions.target import isolation_design

    crit = criteria(args)
    pairs, names = chosen_pairs(args, QUICK_PAIRS)
    suite = scaled_suite(args, pairs, names)  # at --bound, on the --stories superstructure
    building = suite.building
    if not suite.pairs:
        raise SweepError("the scaling rule kept no pair: nothing to design for")
    if not args.quiet:
        print("design:", describe_suite(suite), flush=True)
    gap = design_gap(args, suite.design)
    strain = engine.impact.LAWS["bumper"].PARAMETERS.strain.default
    stress = validity.RUBBER_STRESS_LIMIT if args.stress_limit_mpa is None \
        else args.stress_limit_mpa * 1e6
    for name in ("stress_limit_mpa", "wall_length_m"):
        value = getattr(args, name)
        if value is not None and not value > 0:
            raise SweepError(f"--{name.replace('_', '-')} must be positive, got {value:g}")
    try:
        shape_k = float(SHAPE_K.check(args.shape_k, "--shape-k"))
    except engine.EngineError as err:
        raise SweepError(str(err)) from None
    wall_force = wall_capacity(args)
    # the code's displacement at the service level, by the procedure that gave D_M
    service = isolation_design(suite.site["s_m1"] * LEVELS["service"], building,
                               dashpot=False)
    # the strain at the stress limit depends on the pad's shape (space.usable_strain)
    usable = strain if args.no_stress_limit else \
        functools.partial(usable_strain, strain, stress, shape_k=shape_k)
    bounds = Bounds(gap=gap, clearance=service.d_m, usable_strain=usable,
                    wall_length=args.wall_length_m, shape_factor=shape_range(args))
    if gap - bounds.clearance <= THICKNESS_MIN * bounds.least_usable:
        raise SweepError(f"the gap {gap / CM:.3g} cm leaves no room for bumpers: they must "
                         f"leave D_S = {bounds.clearance / CM:.3g} cm clear (the code's "
                         "displacement at the service level)")
    linear = building.story_law.is_linear
    limits = validity.Limits(
        bumper_stress=stress,
        story_shear=validity.code_story_capacity(suite.basis.force_design, building)
        if linear else None,
        wall_force=wall_force)
    problem = Problem(suite, building, engine.DEFAULT_DT if args.dt is None else args.dt,
                      args.moat, limits, options=run_options(args))
    problem.run_free()
    references = problem.run(reference_members(gap, suite.design.d_tm))
    bare = {name: values[:, :, 1] for name, values in references.items()}
    search = Search(problem, crit, bounds, gap, strain, bare, shape_k)
    coarse = grid(QUICK if args.quick else COARSE, bounds)
    if not coarse["thickness"].size:
        raise SweepError("no layout of the grid fits the bounds: " + bounds.text())
    search.add(coarse, stage=0)
    if not args.quiet:
        print(f"design: coarse grid, {search.stage.size} candidates", flush=True)
    rounds = search.refine(QUICK_ROUNDS if args.quick else ROUNDS, quiet=args.quiet)
    ds = dataset(search, references, rounds, args)
    return ds.assign_attrs({**provenance(problem.swept), **ds.attrs})


# ------------------------------------------------------------------------------ reporting


def plot(ds):
    fig, (left, right) = plt.subplots(1, 2, figsize=(9, 3.8), layout="constrained")
    stress = bool(ds.attrs["stress_limit_counted"])
    within = ds["fraction_within_limits" if stress else "fraction_uncrushed"].isel(
        level=MCE).values
    obj = ds.objective.values / G
    feasible = ds.feasible.values.astype(bool)
    t = ds.thickness.values / CM
    for sel, marker in ((~feasible, "x"), (feasible, "o")):
        points = left.scatter(within[sel], obj[sel], c=t[sel], cmap="viridis", s=14,
                              vmin=t.min(), vmax=t.max(), marker=marker)
    fig.colorbar(points, ax=left, label="thickness (cm)")
    left.axvline(float(ds.attrs["within_limits_required"]), color="k", ls=":", lw=0.8,
                 label="required")
    stat = objective_statistic(ds)
    for j, (name, ls) in enumerate(zip(REFERENCES[1:], ("--", "-."), strict=True), start=1):
        left.axhline(float(ds[f"reference_{stat}"].isel(level=MCE, reference=j)) / G,
                     color="k", ls=ls, lw=0.8, label=name)
    best = int(ds.attrs["closest_candidate"])
    left.plot(within[best], obj[best], marker="*", ms=13, color="C3", ls="none",
              label=("chosen" if feasible[best] else "closest (infeasible)"))
    left.set_xlabel(f"weighted fraction of pairs {'within limits' if stress else 'uncrushed'}"
                    " at the MCE_R")
    left.set_ylabel(f"{OBJECTIVES[ds.attrs['objective']]} largest peak floor accel. (g)")
    left.set_title("Candidates (o feasible, x infeasible)")
    left.legend(fontsize=6)
    rows = [("chosen" if feasible[best] else "closest", "", "candidate", best, "C3")]
    rows += [(name, "reference_", "reference", j, c)
             for j, (name, c) in enumerate(zip(REFERENCES, ("0.6", "C0", "C2"), strict=True))]
    x = np.arange(ds.sizes["level"])
    for k, (name, prefix, dim, i, color) in enumerate(rows):
        med, lo, hi = (ds[f"{prefix}{s}_peak_floor_accel"].isel(**{dim: i}).values / G
                       for s in ("median", "p16", "p84"))
        right.errorbar(x + (k - 1.5) * 0.15, med, yerr=[med - lo, hi - med], fmt="o",
                       color=color, capsize=2, label=name)
    right.set_xticks(x, [str(n) for n in ds.level_name.values])
    right.set_ylabel("largest peak floor acceleration (g): median, 16-84%")
    right.set_title("At each level")
    right.legend(fontsize=6)
    from ..common.plot import letter_panels, short_title, store_caption

    letter_panels((left, right))
    short_title(fig, f"Bumper design at a {float(ds.attrs['design_gap']) / CM:.3g} cm gap")
    store_caption(ds, caption(ds))
    return fig


def caption(ds) -> str:
    """The figure's caption (the archive's figure_caption)."""
    return (f"Bumper design at a {float(ds.attrs['design_gap']) / CM:.3g} cm gap "
            f"({float(ds.attrs['gap_over_D_M']):.2g} D_M), {ds.sizes['record']} pairs; "
            f"optimum {'interior' if ds.attrs['optimum_interior'] else 'at a bound'}. (a) the "
            "candidates (o feasible, x infeasible, colour: thickness) against the references; "
            "(b) the largest peak floor acceleration at each level, median and 16-84%.")


recipe = Recipe(
    name="design", figure="beyond the paper",
    summary="Bumper design search: thickness, cavity, count, size and wall stiffness judged at "
            "the service, design and MCE_R levels on code-scaled record pairs in plan, the "
            "stress limit and crushing as constraints, the code's clearance D_TM beside it",
    compute=compute, plot=plot, check=check, records=(), options=options,
    chosen=(f"gap {GAP_FRACTION:g} D_M; the 22 FEMA P695 far-field pairs as recorded (quick: "
            f"{', '.join(QUICK_PAIRS)}); coarse grid t 4-20 cm, c/t 0-0.4, 4-32 bumpers, S "
            "0.5-1.5, k_w 500 and 2500 kN/mm, then a pattern search; strain and COR the "
            f"law's defaults; the pads' stiffness scaled by their shape factor, Gent & "
            f"Lindley's k = {GENT_LINDLEY_K:g} (unverified for the paper's rubber); wall length "
            f"{WALL_LENGTH:g} m"),
)
main = recipe.main
