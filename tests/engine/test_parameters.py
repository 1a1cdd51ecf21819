"""Each impact law declares its parameters once; the engine, the grid, the archive and the
command line read that declaration. (engine.units: test_units.py.)"""
import dataclasses
import inspect
import json

import numpy as np
import pytest

import engine
import pipeline
from engine import Contact
from engine.impact import LAWS, parameters
from engine.impact.laws import rubber_bumper
from pipeline.errors import SweepError
from pipeline.grid import make_grid
from pipeline.histories import segment


@pytest.mark.parametrize("law", list(LAWS))
def test_constructor_signature_is_the_declaration(law):
    declaration = LAWS[law].PARAMETERS
    signature = inspect.signature(getattr(Contact, law))
    assert list(signature.parameters) == list(declaration)
    for name, entry in declaration.items():
        default = signature.parameters[name].default
        if entry.default is parameters.REQUIRED:
            assert default is inspect.Parameter.empty
        else:
            assert default == entry.default
        assert entry.describe().startswith(name)  # units, range and default in the doc
        assert entry.describe() in getattr(Contact, law).__doc__


def _outside(param):
    """A value just outside the declared range of `param`."""
    low, low_closed, high, high_closed = param.bounds
    if np.isfinite(low):
        return low - 1.0 if low_closed else low
    return high + 1.0 if high_closed else high


@pytest.mark.parametrize("law, name", [(law, name) for law in LAWS
                                       for name in LAWS[law].PARAMETERS.numeric
                                       if name not in ("gap",)])
def test_engine_refuses_values_outside_the_declared_range(law, name):
    declaration = LAWS[law].PARAMETERS
    given = {n: 1e9 for n, e in declaration.numeric.items() if e.required and n != "gap"}
    given[name] = _outside(declaration[name])
    with pytest.raises(engine.EngineError, match=name):
        Contact.of(law, gap=0.3, **given)


def test_integer_parameters_refuse_fractions():
    with pytest.raises(engine.EngineError, match="n_bumpers must be in \\[1, inf\\) and a "
                                                 "whole number"):
        Contact.bumper(0.3, n_bumpers=2.5)


@pytest.mark.parametrize("law", [law for law in LAWS if law != "bumper"])
def test_grid_refuses_in_the_sweep_vocabulary(law):
    """The grid's checks are the declaration's, named as the sweep names them (wall_k)."""
    with pytest.raises(SweepError, match="wall_k must be in \\(0, inf\\)"):
        make_grid(0.2, wall_k=-1.0, impact=law)


def test_grid_defaults_are_the_declared_ones():
    for law in LAWS:
        swept = LAWS[law].PARAMETERS.swept()
        required = {n: 1e10 for n, p in swept.items() if p.required and n != "gap"}
        grid = make_grid(0.2, impact=law, **required)
        for name, value in grid.fixed.items():
            if name in required:
                continue
            expected = 0.2 if name == "gap" else swept[name].default
            assert value == expected, (law, name)


def test_the_archive_reports_what_the_engine_used(monkeypatch, paper_record):
    """Change two declared defaults: a sweep that leaves them out runs the new values, its
    archive's coordinates and provenance say so, and its peaks are those of the engine's own
    constructor under the same (changed) declaration."""
    declaration = rubber_bumper.PARAMETERS
    for name, value in (("cor", 0.6), ("strain", 0.7)):
        monkeypatch.setitem(declaration._entries, name,
                            dataclasses.replace(declaration[name], default=value))
    rec = segment(paper_record("pacoima"), 9.0)
    ds = pipeline.sweep(rec, gap=[0.08, 0.12], workers=0, quiet=True)
    assert float(ds.cor) == 0.6 and float(ds.strain) == 0.7
    assert ds.cor.attrs["long_name"].startswith(declaration.cor.meaning)
    assert ds.strain.attrs["units"] == declaration.strain.units
    defaults = json.loads(ds.attrs["impact_law_defaults"])
    assert defaults["cor"] == 0.6 and defaults["strain"] == 0.7
    direct = engine.simulate(rec.accel, rec.dt, Contact.bumper(np.array([0.08, 0.12])))
    assert np.all(direct.n_impacts > 0)  # the defaults matter here
    np.testing.assert_array_equal(ds.peak_total_accel.isel(record=0), direct.peak_total_accel)
    np.testing.assert_array_equal(ds.max_indentation.isel(record=0), direct.max_indentation)
