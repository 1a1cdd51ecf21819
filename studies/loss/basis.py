"""The collapse archive a loss run reads (--collapse, or the collapse study run first) and the
check that it was run on this run's site, rule, bound and building: its fragilities are then
this building's."""
from __future__ import annotations

import numpy as np

from ..common import collapse_ida as collapse

READ = ("acmr", "beta_total", "collapse_probability", "collapse_probability_bound",
        "collapse_probability_draws", "gap", "gap_fraction", "record", "barrier")
"""The collapse archive's variables the loss study reads."""
BASIS = ("S_MS_g", "S_M1_g", "T_L", "scaling_rule", "isolator_bound")
"""The attributes of a collapse archive that must be this loss run's (pipeline.suite_labels):
the site, the scaling rule and the isolator bound; and every building_* attribute (the
building designed for them, pipeline.provenance.building_attributes)."""


def same_basis(fragility, suite) -> None:
    """SweepError, one line naming the first difference, unless the collapse archive
    `fragility` was run on this loss run's site, rule, bound and building (its gaps, D_TM
    fractions, and its fragilities are theirs: a loss at another site would use them
    silently)."""
    from pipeline.errors import SweepError
    from pipeline.provenance import building_attributes
    from pipeline.suite_labels import archive_variables

    mine = {**archive_variables(suite)[2], **building_attributes(suite.building)}
    theirs = fragility.attrs
    for key in (*BASIS, *sorted(k for k in mine if k.startswith("building_"))):
        a, b = theirs.get(key), mine.get(key)
        if a is None and b is None:
            continue
        if a is None or b is None or not _same(a, b):
            raise SweepError(f"--collapse: the archive was run with {key} = {_text(a)}, this "
                             f"loss run has {_text(b)}: run the collapse study with this "
                             f"run's site, rule, bound and building options, or leave "
                             f"--collapse out to run it now")


def _same(a, b) -> bool:
    """Whether two attribute values are the same (numbers to 1e-12, text exactly)."""
    if isinstance(a, str) or isinstance(b, str):
        return str(a) == str(b)
    a, b = np.atleast_1d(np.asarray(a, dtype=float)), np.atleast_1d(np.asarray(b, dtype=float))
    return a.shape == b.shape and bool(np.allclose(a, b, rtol=1e-12, atol=0.0))


def _text(value) -> str:
    """An attribute value in a message: none when absent, at most 60 characters."""
    if value is None:
        return "none"
    text = str(np.asarray(value).tolist()) if not isinstance(value, str) else value
    return text if len(text) <= 60 else text[:57] + "..."


def collapse_archive(args):
    """(the collapse study's archive, its grid's sweep or None): --collapse (no sweep), or the
    collapse study run now with these options (quick with --quick), whose sweep of every pair
    at its levels the loss study reuses where its stripes are among them."""
    import xarray as xr

    from pipeline.errors import SweepError

    if args.collapse:
        try:
            archive = xr.load_dataset(args.collapse)
        except (OSError, ValueError) as e:
            raise SweepError(f"--collapse: cannot read {args.collapse} ({e})") from None
        if archive.attrs.get("recipe") != "collapse":  # a sweep's, another study's
            made = archive.attrs.get("recipe") or "not a study's"
            raise SweepError(f"--collapse: {args.collapse} is not a collapse study's archive "
                             f"({made}); give the collapse.nc that python -m studies.collapse "
                             "writes, or leave --collapse out to run it now")
        missing = [name for name in READ if name not in archive.variables]
        if missing:  # an archive of an earlier version of the collapse study
            raise SweepError(f"--collapse: {args.collapse} has no {', '.join(missing)} (an "
                             "earlier version of the collapse study wrote it): run python -m "
                             "studies.collapse again, or leave --collapse out to run it now")
        return archive, None
    if not args.quiet:
        print("the collapse fragilities first (studies.collapse)", flush=True)
    return collapse.compute_with_grid(args)
