"""Repair cost and repair time by FEMA P-58 (2018, 2nd edition), through pelicun (an optional
extra: pip install -e ".[loss]"; its FEMA P-58 component database installs with it): a
building's components on its floors, their damage from the peak floor accelerations and
interstory drift ratios each direction, residual drift and collapse; and the losses they
cost. The damage and loss calculation is pelicun's; this module turns the simulator's peaks
into its demand samples and its results into arrays.

Method (FEMA P-58-1 chapters 5 to 7, the intensity-based assessment): at each intensity and
configuration the runs that did not collapse give the demands (studies.loss enters every one,
those outside the model's range as computed); pelicun fits a joint lognormal distribution to
them (FEMA P-58-1 section 5.3, Yang et al. 2009) and draws `samples` realizations. The building
collapses with the collapse fragility's probability at that intensity and is then replaced (the
collapse enters exactly, by its probability: annual_loss.mixture); a realization is irreparable
where its residual drift exceeds the irreparable-drift fragility (replaced too), or else is
repaired, component by component, at the cost and in the time of the component's damage states
(FEMA P-58's consequence functions, with their economies of scale). The residual drift is FEMA
P-58-1 section 5.4's estimate from the peak drift and the story's yield drift (the simulator's
records end while the building still moves).

Units: accelerations m/s^2, drift ratios 1, costs in the database's USD of 2011 (FEMA P-58's
consequence data), repair times in worker-days.
"""
from __future__ import annotations

import csv
import functools
import math
import warnings
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .loss_tables import fragilities, replacement

INVENTORY = Path(__file__).resolve().parents[1] / "data" / "office_inventory.csv"
"""The default inventory of an office building: each component's FEMA P-58 ID, its quantity
per m^2 of floor (per story, or per building m^2, or per story), its unit, where it stands
and its directions. Stated typical quantities, not checked against FEMA P-58's normative
quantity tool: give the building's own table (same columns) where it is known."""
COST_PER_M2 = 3000.0
"""Replacement cost per m^2 of floor, USD of 2011 (a stated choice for an office building)."""
TIME_PER_M2 = 10.0
"""Replacement time per m^2 of floor, worker-days (a stated choice, about pelicun's example's
one worker-day per square foot)."""
IRREPARABLE_DRIFT = (0.01, 0.3)
"""The irreparable residual drift ratio's fragility: median 1%, dispersion 0.3 (FEMA P-58-1
section 7.6's default)."""
SAMPLES = 1000
"""Realizations per intensity and configuration (FEMA P-58-1 section 7: on the order of a
thousand)."""
BATCH = 32
"""Groups assessed at once (`losses`): much of pelicun's time is per assessment (its tables
indexed component by component), which 32 groups of 1000 realizations share (the default
loss study's 120 groups: 100 s one at a time, 24 s in batches; each group's demand model is
still fitted alone); more would hold more of its tables (several columns per component,
location, direction and damage state, for every realization) in memory."""
RUN_SHARE = 0.25
"""The runs' own realizations per group (`run_realizations`) as a share of its fitted model's."""
MIN_RUNS = 3
"""Fewer runs standing than this at an intensity and configuration: no demand model is fitted;
the loss given no collapse there is bounded by the replacement (`losses`: an upper bound, the
output's `bounded` says where)."""
def pelicun():
    """The pelicun module, or a one-line error saying how to install it."""
    try:
        import pelicun as module
        from pelicun import assessment  # noqa: F401 - the submodule this module uses
    except ImportError:
        raise ImportError('the loss assessment needs pelicun: pip install -e ".[loss]"') \
            from None
    return module


def version() -> str:
    """pelicun's version (for the archive's provenance)."""
    return str(pelicun().__version__)


def read_inventory(path=None) -> list[dict]:
    """The inventory's rows (dicts of its CSV columns: component, quantity, per, unit,
    location, direction, description); the default INVENTORY when path is None."""
    path = Path(path) if path is not None else INVENTORY
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
        for r in rows:
            r["quantity"] = float(r["quantity"])
            if r["per"] not in ("m2", "story", "building_m2"):
                raise ValueError(f"'per' is m2, story or building_m2, got {r['per']!r}")
            if r["location"] not in ("stories", "ground", "roof"):
                raise ValueError(f"'location' is stories, ground or roof, got "
                                 f"{r['location']!r}")
            r["component"], r["unit"], r["direction"] = (r["component"], r["unit"],
                                                         r["direction"])
    except (OSError, KeyError, ValueError, TypeError) as e:
        raise ValueError(f"inventory {path}: {e}") from None
    if not rows:
        raise ValueError(f"inventory {path}: no components")
    return rows


def marginals(rows, stories: int, floor_area: float):
    """pelicun's component marginals (a DataFrame) for a building of `stories` stories of
    floor_area m^2 each: each row's quantity per floor, placed on every story (locations 1..N),
    at the ground floor (1, the isolated base) or on the roof (N + 1); plus the irreparable
    placeholders pelicun's damage process needs."""
    import pandas as pd

    out = {}
    for r in rows:
        quantity = {"m2": r["quantity"] * floor_area, "story": r["quantity"],
                    "building_m2": max(1.0, math.ceil(r["quantity"] * floor_area * stories))
                    }[r["per"]]
        where = {"stories": f"1--{stories}" if stories > 1 else "1", "ground": "1",
                 "roof": str(stories + 1)}[r["location"]]
        out[r["component"]] = [r["unit"], where, r["direction"], quantity, 1]
    out["excessiveRID"] = ["ea", "all", "1,2", 1.0, 1]
    out["irreparable"] = ["ea", "0", "1", 1.0, 1]
    return pd.DataFrame.from_dict(out, orient="index",
                                  columns=["Units", "Location", "Direction", "Theta_0",
                                           "Blocks"])


def raw_demands(pfa, pid):
    """pelicun's raw demand table (a DataFrame with its Units row) from the runs' peak floor
    accelerations pfa (R, N+1, 2) m/s^2 (levels 0, the isolated base, to N, the roof; x and
    y) and peak interstory drift ratios pid (R, N, 2): PFA at locations 0..N, PID at 1..N,
    directions 1 and 2 (pelicun reads a story's acceleration-sensitive components at the
    floor below, or above with their offset)."""
    import pandas as pd

    pfa, pid = np.asarray(pfa, float), np.asarray(pid, float)
    columns, values = [], []
    for k in range(pfa.shape[1]):
        for d in range(2):
            columns.append(("PFA", str(k), str(d + 1)))
            values.append(pfa[:, k, d])
    for k in range(pid.shape[1]):
        for d in range(2):
            columns.append(("PID", str(k + 1), str(d + 1)))
            values.append(pid[:, k, d])
    index = pd.MultiIndex.from_tuples(columns, names=["type", "loc", "dir"])
    table = pd.DataFrame(np.array(values).T, columns=index).astype(object)
    units = pd.DataFrame([["mps2"] * (2 * pfa.shape[1]) + ["unitless"] * (2 * pid.shape[1])],
                         columns=index, index=["Units"])
    return pd.concat([table, units])


@dataclass(frozen=True)
class Group:
    """One intensity and configuration: its runs' peaks pfa (R, N+1, 2) m/s^2 and
    pid (R, N, 2), and the collapse fragility's standard deviate there, ln(level / median) /
    beta (P(collapse) = Phi(deviate))."""

    pfa: np.ndarray
    pid: np.ndarray
    collapse_deviate: float


def options(seed: int) -> dict:
    """pelicun's configuration: silent and seeded."""
    return {"PrintLog": False, "Verbose": False, "Seed": int(seed)}


def losses(groups, rows, *, stories: int, floor_area: float, yield_drift: float,
           replacement_cost: float | None = None, replacement_time: float | None = None,
           samples: int = SAMPLES, seed: int = 1, progress=None) -> dict:
    """Each group's loss realizations given no collapse, every group with the same seed
    (common random numbers: realization k of every group draws the same component quantities
    and capacities, so that the groups differ by their demands, not by sampling noise; the
    consequences too within a batch of BATCH groups, pelicun drawing one per component and
    damage state that the batch's realizations reach).

    groups: sequence of Group (None where no demand model is fitted); rows: the inventory
    (read_inventory); yield_drift: the stories' yield drift ratio for the residual drift
    estimate; replacement cost (USD 2011) and time (worker-days) default to COST_PER_M2 and
    TIME_PER_M2 of the total floor area. Returns repair_cost (USD 2011) and repair_time
    (worker-days, the parallel repair time) (G, samples) given no collapse, irreparable (G,
    samples) bool, repair_cost_by_group (G, samples, COMPONENT_GROUPS) summing repair_cost,
    run_repair_cost (G, max runs) each run's own mean repair cost given no collapse (its
    demands assessed as they are, no model fitted, `_runs_sample`: for the record-to-record
    spread of the mean, a bootstrap's; NaN beyond a group's runs),
    collapse_probability (G,) (Phi of the group's deviate), bounded (G,) bool,
    replacement_cost and replacement_time. A group of fewer than MIN_RUNS runs has no demand
    model: its loss given no collapse is taken at its upper bound, the replacement (every
    realization irreparable, replaced: `bounded`), its collapse probability its own; a group
    None is NaN (False) throughout. The collapse enters exactly, not sampled (FEMA P-58-1
    Eq. 7-1: P(C) times the replacement plus (1 - P(C)) times the loss given no collapse):
    annual_loss.mixture gives its statistics. progress: None, or called with no argument as
    each group is done (BATCH groups at a time, sharing one pelicun assessment, `_assess`;
    every other batch in a second process where there are two cores, the same numbers)."""
    pelicun()
    from scipy.stats import norm

    area = floor_area * stories
    cost = COST_PER_M2 * area if replacement_cost is None else replacement_cost
    time = TIME_PER_M2 * area if replacement_time is None else replacement_time
    out = {"repair_cost": np.full((len(groups), samples), np.nan),
           "repair_time": np.full((len(groups), samples), np.nan),
           "repair_cost_by_group": np.full((len(groups), samples, len(COMPONENT_GROUPS)),
                                           np.nan),
           "irreparable": np.zeros((len(groups), samples), bool),
           "collapse_probability": np.full(len(groups), np.nan),
           "bounded": np.zeros(len(groups), bool),
           "run_repair_cost": np.full((len(groups), max((len(g.pfa) for g in groups
                                                         if g is not None), default=0)),
                                      np.nan),
           "replacement_cost": cost, "replacement_time": time}
    for g, group in enumerate(groups):
        if group is not None:
            out["collapse_probability"][g] = norm.cdf(group.collapse_deviate)
            if len(group.pfa) < MIN_RUNS:  # no demand model: at most the replacement
                out["bounded"][g] = out["irreparable"][g] = True
                out["repair_cost"][g], out["repair_time"][g] = cost, time
                out["repair_cost_by_group"][g] = 0.0
                out["repair_cost_by_group"][g, :, COMPONENT_GROUPS.index(REPLACED)] = cost
                out["run_repair_cost"][g, :len(group.pfa)] = cost
    modelled = [g for g, group in enumerate(groups)
                if group is not None and len(group.pfa) >= MIN_RUNS]
    if not modelled:
        return out
    setting = (tuple(tuple(sorted(r.items())) for r in rows), stories, floor_area, cost, time,
               seed, yield_drift, samples)
    batches = [modelled[start:start + BATCH] for start in range(0, len(modelled), BATCH)]
    # every other batch to a second process where there are two cores (pelicun holds the GIL):
    # each batch draws what it would draw alone (its generator seeded anew), in any process
    pool = _helper() if len(batches) > 1 else None
    theirs = {}
    if pool is not None:
        from pipeline.execute.dask_client import main_hidden

        with main_hidden():  # the helper must not re-run a script without a __main__ guard
            theirs = {k: pool.submit(_assess_elsewhere, setting, [groups[g] for g in batch])
                      for k, batch in enumerate(batches) if k % 2}
    try:
        for k, batch in enumerate(batches):
            some = theirs[k].result() if k in theirs else \
                _assess_with(setting, [groups[g] for g in batch])
            runs = some.pop("run_repair_cost")
            out["run_repair_cost"][batch, :runs.shape[1]] = runs
            for name, value in some.items():
                out[name][batch] = value
            if progress is not None:
                for _ in batch:
                    progress()
    finally:
        _ASSESSMENTS.clear()  # pelicun's tables freed, as the assessment went out of scope
        if pool is not None:
            pool.shutdown(cancel_futures=True)
    return out


def _helper():
    """One more process for `losses`' batches where this one may run on two cores or more
    (spawned: a clean interpreter, whatever threads this one runs), else None."""
    import multiprocessing
    import os
    from concurrent.futures import ProcessPoolExecutor

    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    return ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn")) \
        if (cores or 1) > 1 else None


_ASSESSMENTS: dict = {}
"""setting -> the pelicun assessment `_assess_with` built for it, in this process."""


def _assess_with(setting, groups) -> dict:
    """`_assess` of the groups on the assessment of `setting` (rows as sorted items, stories,
    floor_area, replacement cost and time, seed, yield_drift, samples), built once a process."""
    rows, stories, floor_area, cost, time, seed, yield_drift, samples = setting
    if setting not in _ASSESSMENTS:
        _ASSESSMENTS.clear()  # one building's at a time
        table = [dict(r) for r in rows]
        _ASSESSMENTS[setting] = _assessment(
            marginals(table, stories, floor_area),
            database(tuple(r["component"] for r in table)), stories, cost, time, seed)
    return _assess(groups, _ASSESSMENTS[setting], yield_drift, samples, seed)


def _assess_elsewhere(setting, groups) -> dict:
    """`_assess_with` in the helper process (pelicun imported there first)."""
    pelicun()
    return _assess_with(setting, groups)


@functools.cache
def _default_data():
    """pelicun's FEMA P-58 fragility and repair consequence tables (read once a process: the
    inventory is checked before the simulations and its rows taken after them)."""
    from pelicun.assessment import Assessment

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        a = Assessment(options(0))
        return (a.get_default_data("FEMA P-58", "fragility"),
                a.get_default_data("FEMA P-58", "consequence_repair"))


def unknown_components(rows) -> list[str]:
    """The component IDs of inventory rows (read_inventory) that FEMA P-58's fragility
    database (pelicun's) does not hold, sorted."""
    return sorted({r["component"] for r in rows} - set(_default_data()[0].index))


def database(components: tuple[str, ...]):
    """(fragilities, repair consequences): FEMA P-58's rows of these components (pelicun's
    default database), the cost and time consequences only."""
    fragility, repair = _default_data()
    missing = sorted(set(components) - set(fragility.index))
    if missing:
        raise ValueError(f"inventory: not in FEMA P-58's fragility database: "
                         f"{', '.join(missing)}")
    keep = repair.index.get_level_values(0).isin(components) \
        & repair.index.get_level_values(1).isin(("Cost", "Time"))
    return fragility.loc[list(components)], repair[keep]


def _assessment(assets, data, stories, cost, time, seed):
    """A pelicun assessment with the building's components, their fragilities and
    consequences loaded (once: pelicun converts the consequences' units cell by cell, most of
    an assessment's time); `_assess` runs each group on it."""
    import pandas as pd
    from pelicun.assessment import Assessment

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # pelicun's notes on the database's incomplete rows
        a = Assessment(options(seed))
        a.stories = stories
        a.asset.load_cmp_model({"marginals": assets})
        a.asset.generate_cmp_sample(1)
        a.damage.load_model_parameters([fragilities(*IRREPARABLE_DRIFT), data[0]],
                                       sorted(a.asset.list_unique_component_ids()))
        a.loss.decision_variables = ("Cost", "Time")
        # The loss map written out in a fixed order (pelicun's "fill" policy builds it from a
        # set, whose order, and so the draws' order, changes with Python's hash seed).
        components = sorted(c for c in a.asset.list_unique_component_ids()
                            if c not in ("excessiveRID", "irreparable"))
        a.loss.add_loss_map(pd.DataFrame({"Repair": [*components, "replacement"]},
                                         index=[*components, "irreparable"]),
                            loss_map_policy=None)
        a.loss.load_model_parameters([replacement(cost, time), data[1]])
    return a


def _assess(groups, a, yield_drift, samples, seed) -> dict:
    """The groups on the loaded assessment `a` at once: each group's demand model fitted and
    sampled alone, its random generator reset to `seed` first; their samples stacked, one
    damage and loss calculation over them all, its draws (component quantities, capacities,
    consequences) made for one group's `samples` realizations and repeated for each
    (`common_draws`): every group draws the same numbers, as if assessed alone. Returns
    repair_cost, repair_time and irreparable (len(groups), samples), given no collapse,
    repair_cost_by_group (len(groups), samples, COMPONENT_GROUPS), which sums repair_cost, and
    run_repair_cost (len(groups), max runs): each run's mean repair cost on its own demands
    (`_runs_sample`, assessed in the same calculation on the same draws)."""
    import pandas as pd

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        stacked = []
        for group in groups:
            a.options.seed = seed
            stacked.append(_demand_sample(a, raw_demands(group.pfa, group.pid), yield_drift,
                                          fitted=samples))
        # the generator now stands where each group's own assessment would draw on from: the
        # runs' own demands below draw their residual drifts from a generator of their own
        state = a.options.rng.bit_generator.state
        per_run = run_realizations(samples)
        for group in groups:
            a.options.seed = seed + 1
            stacked.append(_runs_sample(a, group, per_run, yield_drift))
        a.options.rng.bit_generator.state = state
        a.demand.sample = pd.concat(stacked, ignore_index=True)
        which = np.concatenate([np.tile(np.arange(samples), len(groups)),
                                np.tile(np.arange(per_run), len(groups))])
        with common_draws(which, samples):
            a.asset.generate_cmp_sample(which.size)
            a.damage.calculate(dmg_process={"1_excessiveRID": {"DS1": "irreparable_DS1"}})
            a.loss.calculate()
            # pelicun keeps the component losses in pandas' nullable dtypes, a block a column:
            # its sum over components transposes them into a block a realization (1.1 s for
            # 8000 realizations); as float64 the same sums take 0.07 s, equal to round-off
            # (4e-16 relative: the order of the additions)
            for model in (a.loss.ds_model, a.loss.lf_model):
                if model.sample is not None:
                    model.sample = model.sample.astype("float64")
            total, _ = a.loss.aggregate_losses(future=True)
        damage = a.damage.ds_model.sample
        by_loss = a.loss.ds_model.sample.xs("Cost", axis=1, level="dv").T \
            .groupby(level="loss").sum().T  # realizations x components (and "replacement")
    # the damaged quantity of the placeholder in its damage state 1 (0: undamaged)
    part = damage.xs("irreparable", axis=1, level="cmp")
    hit = part.loc[:, part.columns.get_level_values("ds") != "0"].to_numpy(float)
    shape = (len(groups), samples)
    model = slice(0, len(groups) * samples)  # the fitted model's realizations; then the runs'
    kinds = [component_group(c) for c in by_loss.columns]
    parts = np.stack([by_loss.loc[:, [k == g for k in kinds]].to_numpy(float).sum(axis=1)
                      for g in range(len(COMPONENT_GROUPS))], axis=-1)
    cost = total[("repair_cost", "")].to_numpy(float)
    return {"repair_cost": cost[model].reshape(shape),
            "repair_time": total[("repair_time", "parallel")].to_numpy(float)[model]
            .reshape(shape),
            "irreparable": (np.nan_to_num(hit).sum(axis=1) > 0)[model].reshape(shape),
            "repair_cost_by_group": parts[model].reshape(*shape, -1),
            "run_repair_cost": run_means(cost[len(groups) * samples:].reshape(len(groups), -1),
                                         [len(g.pfa) for g in groups])}


def run_realizations(samples: int) -> int:
    """Realizations of a group's runs' own demands (`_runs_sample`) beside `samples` of its
    fitted model: RUN_SHARE of them (at least one), several a run (44 runs: 5 or 6 each of
    the default's 250), enough for the runs' relative spread and a quarter of the cost."""
    return max(1, int(samples * RUN_SHARE))


def _runs_sample(a, group, samples: int, yield_drift: float):
    """pelicun's demand sample of `samples` realizations on the group's runs themselves, no
    model fitted: realization k takes run k mod R's demands (their residual drifts estimated
    as the fitted model's are), so that each run's mean loss is known (`run_means`)."""
    import pandas as pd

    raw = raw_demands(group.pfa, group.pid)
    runs = raw.drop(index="Units")
    tiled = runs.iloc[np.arange(samples) % len(runs)].reset_index(drop=True)
    return _demand_sample(a, pd.concat([tiled, raw.loc[["Units"]]]), yield_drift)


def _demand_sample(a, raw, yield_drift: float, fitted: int | None = None):
    """pelicun's demand sample of assessment `a` from the raw demands (raw_demands' table):
    with `fitted`, that many realizations of the joint lognormal fitted to them (FEMA P-58-1
    section 5.3), else the rows themselves; residual drifts estimated (section 5.4)."""
    from pelicun.model import DemandModel

    a.demand = DemandModel(a)
    a.demand.load_sample(raw)
    if fitted is not None:
        a.demand.calibrate_model({"ALL": {"DistributionFamily": "lognormal"}})
        a.demand.generate_sample({"SampleSize": fitted})
    a.demand.estimate_RID_and_adjust_sample({"yield_drift": yield_drift})
    a.demand.expand_sample("ONE", 1.0, "unitless")
    return a.demand.sample


def run_means(realizations, runs) -> np.ndarray:
    """(G, max(runs)) each run's mean over the realizations (G, S) that took its demands
    (realization k: run k mod R of its group's R = runs[g]); NaN beyond a group's runs."""
    x = np.asarray(realizations, float)
    out = np.full((x.shape[0], max(runs, default=0)), np.nan)
    for g, r in enumerate(runs):
        which = np.arange(x.shape[1]) % r
        out[g, :r] = np.bincount(which, weights=x[g], minlength=r) / np.bincount(which,
                                                                                  minlength=r)
    return out


REPLACED = "irreparable (replaced)"
COMPONENT_GROUPS = ("acceleration-sensitive", "drift-sensitive", REPLACED)
"""What a realization's repair cost given no collapse sums (pelicun's: the components' costs,
and the replacement where the residual drift makes the building irreparable): the components
whose FEMA P-58 fragility reads a floor acceleration, the others (story drift), and the
replacement."""


def component_group(loss: str) -> int:
    """The COMPONENT_GROUPS index of one of pelicun's loss columns: a component by its
    fragility's demand type in FEMA P-58's database, or the replacement."""
    if loss == "replacement":
        return COMPONENT_GROUPS.index(REPLACED)
    return 0 if "Acceleration" in str(_default_data()[0].loc[loss, ("Demand", "Type")]) else 1


@contextmanager
def common_draws(which, samples: int):
    """Within it, pelicun's random variables asked for len(which) realizations draw `samples`
    and give realization k the draw which[k] (common random numbers across the stacked groups
    of `_assess`: each group's realizations take the draws 0, 1, ... from the start, those of
    one group's assessment, in the same order from the same generator). Other sizes draw as
    pelicun does."""
    from pelicun.uq import RandomVariableRegistry

    draw = RandomVariableRegistry.generate_sample
    which = np.asarray(which, int)

    def repeated(registry, sample_size, method):
        if sample_size != which.size or which.size == samples:
            return draw(registry, sample_size, method)
        draw(registry, samples, method)
        for rv in registry.RV.values():
            if rv._sample is not None:
                rv._sample = rv._sample[which]
        return None

    RandomVariableRegistry.generate_sample = repeated
    try:
        yield
    finally:
        RandomVariableRegistry.generate_sample = draw
