"""What studies.suite's archive holds and how its verdicts and figure read it: the bumpers'
crush limit, the configurations' variable prefixes, the responses, the outcomes, the
quantifiers' wording, and the accessors (a response with or without bumpers, contact, runs
outside the model's range, the runs a case counts). Shared by the recipe (__init__.py),
verdicts.py and figure.py."""
from __future__ import annotations

import numpy as np

from pipeline.assess import derived
from pipeline.assess.outcomes import ALMOST_EVERY

PREFIX = {"bumpers": "", "bare": "bare_", "free": "free_"}
"""Archive prefix of each configuration's variables: bumpers, the bare wall, no wall."""


RESPONSES = {
    "base_accel": "peak base (isolation level) acceleration",
    "floor_accel": f"{derived.quantity('peak_floor_accel').long_name} (base included)",
    # pipeline.assess.derived's peak_story_drift, in the paper's word, as the archives have it
    "interstory_drift": "largest peak interstory deflection",
}


OUTCOMES = ("helped", "neutral", "hurt", "no_contact")


QUANTIFIER_TEXT = {
    "every": "at every counted case", "most": "at more than half the counted cases where it "
    "changes", "almost every": f"at {ALMOST_EVERY:.0%} at least of the counted cases where "
    "it changes", "some": "at one counted case at least"}


def response(ds, name: str, config: str = "bumpers"):
    """The response `name` (RESPONSES, or "upper_accel": the largest over the floors above the
    base) of a configuration's runs: the largest ones as pipeline.assess.derived computes them."""
    prefix = PREFIX[config]
    accel = ds[prefix + "peak_total_accel"]
    largest = derived.largest_floor_accel
    return {"base_accel": lambda: accel.isel(floor=0),
            "floor_accel": lambda: _over(accel, "floor", largest),
            "upper_accel": lambda: _over(accel.isel(floor=slice(1, None)), "floor", largest),
            "interstory_drift": lambda: _over(ds[prefix + "peak_interstory_drift"], "story",
                                              derived.largest_story_drift),
            }[name]()


def _over(values, dim: str, function):
    """A DataArray reduced over `dim` by a function of arrays reducing their last axis."""
    import xarray as xr

    return xr.apply_ufunc(function, values, input_core_dims=[[dim]])


def contact(ds):
    """(record, level, gap_fraction, n_bumpers, wall_k) bool: the bumpers or the bare wall at
    the same gap are hit."""
    return (ds.n_impacts > 0) | (ds.bare_n_impacts > 0)


def outside(ds, config: str):
    """A configuration's runs outside the model's range (any invalid_* flag): a bool
    DataArray over the configuration's dims."""
    from functools import reduce

    from pipeline.assess.validity import FLAGS

    prefix = PREFIX[config]
    return reduce(lambda a, b: a | b, [ds[prefix + name].astype(bool) for name in FLAGS])


def broadcast_weights(w, shape):
    """(R,) weights broadcast over (R, ...)."""
    return np.broadcast_to(np.reshape(w, (-1,) + (1,) * (len(shape) - 1)), shape)


POINT = ("record", "level", "gap_fraction")  # a case: one pair at one level and gap


def runs(ds, n=None, k=None) -> dict:
    """One configuration's runs over (record, level, gap_fraction) as arrays: the bumpers (n,
    k) or, with n None, the bare wall. Keys: base, upper, floor, drift (responses), force,
    indentation, hit (bool), outside (name of the flag -> bool), outside_any (bool),
    collapse_mode (int8: how the run ended, engine.results.COLLAPSE_MODES)."""
    from pipeline.assess.validity import FLAGS

    config = "bare" if n is None else "bumpers"
    at = {} if n is None else {"n_bumpers": n, "wall_k": k}
    prefix = PREFIX[config]

    def get(value):
        return value.sel(**at).transpose(*POINT).values

    out = {key: get(response(ds, name, config)) for key, name in (
        ("base", "base_accel"), ("upper", "upper_accel"), ("floor", "floor_accel"),
        ("drift", "interstory_drift"))}
    out["force"] = get(ds[prefix + "max_impact_force"])
    out["indentation"] = get(ds[prefix + "max_indentation"])
    out["hit"] = get(ds[prefix + "n_impacts"]) > 0
    out["outside"] = {name: get(ds[prefix + name]).astype(bool) for name in FLAGS}
    out["outside_any"] = np.any(list(out["outside"].values()), axis=0)
    out["collapse_mode"] = get(ds[prefix + "collapse_mode"])
    return out
