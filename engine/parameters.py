"""How a law declares its parameters: once, with unit, valid range, default, meaning and the
paper's equation (in the manner of pygmm's model declarations).

Every impact law and every isolator law holds one `Declaration`. The constructors
(`Contact.bumper(...)`, `Isolator.friction_pendulum(...)`: `law_constructor`), the sweep
grid's defaults and checks, the archive's `units` / `long_name` attributes and provenance, and
the command line's help all read it, so a default or a range is changed in one line, in the
law's module. Ranges are written in interval notation, e.g. "(0, 1]" or "[1, inf)".
"""
from __future__ import annotations

import inspect
import re
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from .errors import EngineError

REQUIRED = object()
"""Default of a parameter the caller must give."""

_INTERVAL_RE = re.compile(r"^\s*([\[(])\s*(\S+?)\s*,\s*(\S+?)\s*([\])])\s*$")


def interval(name: str, text: str) -> tuple[float, bool, float, bool]:
    """(low, low closed, high, high closed) of interval notation such as '(0, 1]'."""
    m = _INTERVAL_RE.match(text)
    if m is None:
        raise ValueError(f"{name}: an interval must read like '(0, 1]', got {text!r}")
    return float(m.group(2)), m.group(1) == "[", float(m.group(3)), m.group(4) == "]"


def outside(array: np.ndarray, bounds: tuple[float, bool, float, bool]) -> np.ndarray:
    """Where `array` lies outside the interval `bounds` (interval's tuple; NaN included)."""
    low, low_closed, high, high_closed = bounds
    above = array >= low if low_closed else array > low
    below = array <= high if high_closed else array < high
    return ~(above & below)  # NaN fails both


_UNIT_TOKEN = re.compile(r"^([A-Za-z]+)(?:\^?\(?(-?\d+(?:\.\d+)?)\)?)?$")
_UNIT_NAMES = r"(?:N|kN|MN|m|mm|cm|km|s|ms|kg|t|Pa|kPa|MPa|GPa|J|kJ|W|rad|degree)"
_UNIT_IN_TEXT = re.compile(
    rf"(?<![\w.^/-])((?:{_UNIT_NAMES}(?:\d+(?:\.\d+)?)? )*"
    rf"{_UNIT_NAMES}(?:-\d+(?:\.\d+)?|\^\(-\d+(?:\.\d+)?\))"
    rf"(?: {_UNIT_NAMES}(?:-?\d+(?:\.\d+)?|\^\(-?\d+(?:\.\d+)?\))?)*)(?![\w^(])")
"""A UDUNITS-style unit inside prose ('N m-1', 's m-1', 'N m^(-1.5)', 'm s-2'): known unit
names with powers, at least one of them negative (so that ordinary words never match)."""
_INTERNAL = (
    (re.compile(r"\s*\(SPEC decision\)"), " (a value chosen here: the paper does not state it)"),
    (re.compile(r";\s*SPEC decision\)"), "; a value chosen here: the paper does not state it)"),
    (re.compile(r"SPEC decision"), "a value chosen here: the paper does not state it"),
    (re.compile(r"(?:,|;)?\s*\bSPEC(?:'s)? (?:section )?\d+(?:\.\d+)*(?=[),;:]|$)"), ""),
    (re.compile(r"\bSPEC:\s*"), ""),
    (re.compile(r"\bthe SPEC's\b|\bSPEC's\b"), "the model's"),
    (re.compile(r"\bSPEC\b"), "the model"),
    (re.compile(r"(?:,|;)?\s*(?:\.\./shared|tests)/[\w./-]*"), ""),
    (re.compile(r"\(\s*\)"), ""),
    (re.compile(r"\(\s*[;,]\s*"), "("),
)
"""Internal references (the project's specification, its test files, its shared folders) and
the plain words a user reads instead; a reference that only pointed there is dropped."""


def unit_text(units: str) -> str:
    """A UDUNITS-style unit string in the paper's spelling: 'N m-1' -> 'N/m', 'N m^(-1.5)'
    -> 'N/m^1.5', 'm s-2' -> 'm/s^2', 's m-1' -> 's/m', '1' -> '' (a pure number). A string
    that is not such a unit (already 'kN/mm', or words) comes back as it is."""
    units = units.strip()
    if units in ("", "1"):
        return ""
    above, below = [], []
    for token in units.split():
        m = _UNIT_TOKEN.match(token)
        if m is None:
            return units
        name, power = m.group(1), float(m.group(2)) if m.group(2) else 1.0
        (above if power > 0 else below).append(name if abs(power) == 1 else
                                               f"{name}^{abs(power):g}")
    if not below:
        return " ".join(above)
    under = below[0] if len(below) == 1 else f"({' '.join(below)})"
    return f"{' '.join(above) or '1'}/{under}"


def user_text(text: str) -> str:
    """Text for a user (help, warnings, summaries): units in the paper's spelling (unit_text)
    and plain words instead of internal references (the project's specification, test files
    and shared folders); a paper's equation or a standard's clause stays."""
    text = _UNIT_IN_TEXT.sub(lambda m: unit_text(m.group(1)), text)
    for pattern, plain in _INTERNAL:
        text = pattern.sub(plain, text)
    return text


@dataclass(frozen=True)
class Parameter:
    """One numeric parameter of an impact or isolator law.

    name: keyword of the law's constructor (Contact.of, Isolator.of); units: UDUNITS-style
    string of the SI unit; meaning: one line (the archive's long_name); default: a number, None
    (optional, unset) or REQUIRED; valid: interval notation of the values accepted; integer:
    whole numbers only; equation: where the paper defines it; sweep: its name among
    pipeline.sweep's parameters (None: not swept, it stays at its default in sweeps); plausible:
    interval of the values a real structure has (None: any valid value), outside which the
    pipeline refuses a value as a likely unit slip.
    """

    name: str
    units: str
    meaning: str
    default: object
    valid: str = "(-inf, inf)"
    integer: bool = False
    equation: str = ""
    sweep: str | None = None
    plausible: str | None = None
    bounds: tuple = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        object.__setattr__(self, "bounds", interval(self.name, self.valid))
        if self.plausible is not None:
            interval(self.name, self.plausible)

    def implausible(self, values) -> np.ndarray:
        """The values outside the `plausible` interval: valid to the engine, but what no real
        building, bumper or wall has (most likely a value in another unit, e.g. kN/mm given
        as N/m). Checked by the pipeline and the commands, not by the engine, so that a
        laboratory model can still be simulated directly."""
        array = np.atleast_1d(np.asarray(values, dtype=float))
        if self.plausible is None:
            return array[:0]
        return array[outside(array, interval(self.name, self.plausible))]

    @property
    def required(self) -> bool:
        return self.default is REQUIRED

    def check(self, value, name: str | None = None) -> np.ndarray:
        """`value` as a float array, or EngineError naming the parameter (as `name` if given:
        the caller's vocabulary, e.g. the sweep's wall_k for a bumper's k_w)."""
        name = name or self.name
        try:
            array = np.asarray(value, dtype=float)
        except (TypeError, ValueError):
            raise EngineError(f"{name} must be a number or an array of numbers, "
                              f"got {value!r}") from None
        bad = outside(array, self.bounds)
        if self.integer:
            bad |= array != np.round(array)
        if np.any(bad):
            rule = f"in {self.valid}" + (" and a whole number" if self.integer else "")
            unit = "" if self.units == "1" else f" {self.units}"
            raise EngineError(f"{name} must be {rule}{unit}, got {np.atleast_1d(array)[bad]}")
        return array

    def value_text(self, value) -> str:
        """'k = 2.5e+09 N m-1', 'cor = 0.5': a value of this parameter with its unit."""
        return f"{self.name} = {value:g}" + ("" if self.units == "1" else f" {self.units}")

    def describe(self) -> str:
        """'thickness: bumper thickness t, m, in (0, inf), default 0.05 (Eq. 11)': the unit in
        the paper's spelling (user_text), written once."""
        default = ("required" if self.required else "unset" if self.default is None
                   else f"default {self.default:g}")
        return f"{self.name}: {self.help_text()}, in {self.valid}, {default}" + (
            f" ({user_text(self.equation)})" if user_text(self.equation) else "")

    def help_text(self) -> str:
        """'bumper thickness t, m': the meaning and the unit for a reader (the paper's
        spelling, N/m^1.5 for N m^(-1.5); the unit left out when the meaning already says
        it; no unit for a pure number)."""
        meaning, units = user_text(self.meaning), unit_text(self.units)
        if not units or meaning.endswith(units) or ("/" in units and units in meaning):
            return meaning
        return f"{meaning}, {units}"


@dataclass(frozen=True)
class Option:
    """A choice of rule, e.g. how a damping constant is derived from the COR."""

    name: str
    choices: tuple[str, ...]
    default: str
    meaning: str

    def check(self, value) -> str:
        if value not in self.choices:
            raise EngineError(f"{self.name} must be one of {self.choices}, got {value!r}")
        return value

    def describe(self) -> str:
        return (f"{self.name}: {user_text(self.meaning)}, one of {self.choices}, "
                f"default {self.default!r}")


class Declaration(Mapping):
    """A law's parameters and options in constructor order: name -> Parameter | Option.

    Attribute access reads an entry: ``rubber_bumper.PARAMETERS.cor.default``.
    """

    def __init__(self, *entries: Parameter | Option):
        self._entries = {e.name: e for e in entries}
        if len(self._entries) != len(entries):
            raise ValueError("a declaration names each parameter once")

    def __getitem__(self, name):
        return self._entries[name]

    def __iter__(self):
        return iter(self._entries)

    def __len__(self):
        return len(self._entries)

    def __getattr__(self, name):
        try:
            return self.__dict__["_entries"][name]
        except KeyError:
            raise AttributeError(name) from None

    @property
    def numeric(self) -> dict[str, Parameter]:
        return {n: e for n, e in self.items() if isinstance(e, Parameter)}

    def defaults(self) -> dict:
        """name -> default of every entry that has one (provenance of a run)."""
        return {n: e.default for n, e in self.items() if e.default is not REQUIRED}

    def swept(self) -> dict[str, Parameter]:
        """sweep name -> Parameter, for the parameters pipeline.sweep can vary."""
        return {e.sweep: e for e in self.numeric.values() if e.sweep is not None}

    def resolve(self, given: dict) -> dict:
        """Every entry's value: given ones checked, the others at their defaults.

        Numeric values come back as float arrays (not yet broadcast); EngineError for an
        unknown name, a missing required one or a value out of range.
        """
        unknown = sorted(set(given) - set(self))
        if unknown:
            raise EngineError(f"unknown parameter(s) {unknown}; this law takes "
                              f"{', '.join(self)}")
        values = {}
        for name, entry in self.items():
            value = given.get(name, entry.default)
            if value is REQUIRED:
                raise EngineError(f"{name} is required ({entry.units})")
            if isinstance(entry, Option):
                values[name] = entry.check(value)
            else:
                values[name] = None if value is None else entry.check(value)
        return values

    def describe(self) -> str:
        return "\n".join("    " + e.describe() for e in self.values())


def law_constructor(owner: str, law: str, declaration: Declaration, doc: str, build,
                    keyword_only: bool = False):
    """A classmethod `<owner>.<law>(...)` whose signature and docstring are the law's
    declaration (in order, each with its default), so that the declaration is the only place
    defaults and ranges are written; it calls build(cls, law, **arguments). keyword_only:
    every parameter by name (a declaration may then list required ones after defaults)."""
    kind = inspect.Parameter.KEYWORD_ONLY if keyword_only \
        else inspect.Parameter.POSITIONAL_OR_KEYWORD
    signature = inspect.Signature(
        [inspect.Parameter(name, kind,
                           default=inspect.Parameter.empty if entry.default is REQUIRED
                           else entry.default)
         for name, entry in declaration.items()])

    def constructor(cls, *args, **kwargs):
        try:
            bound = signature.bind(*args, **kwargs)
        except TypeError as err:
            raise EngineError(f"{owner}.{law}: {err}") from None
        return build(cls, law, **bound.arguments)

    constructor.__name__ = constructor.__qualname__ = law
    constructor.__signature__ = signature.replace(
        parameters=[inspect.Parameter("cls", inspect.Parameter.POSITIONAL_ONLY),
                    *signature.parameters.values()])
    constructor.__doc__ = doc + "\n" + declaration.describe()
    return classmethod(constructor)
