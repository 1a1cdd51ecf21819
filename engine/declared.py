"""How a component of the building declares its fields: once, at the field, with unit, shape,
valid and plausible range, meaning and default (the way engine/parameters.py declares a law's
parameters).

    masses: tuple = declared(PAPER_MASSES, "kg", "mass of each level", per="level",
                             valid="(0, inf)", plausible="[1e3, 1e9]")

`declared` is a dataclasses.field whose metadata holds the Field; `fields_of(cls)` reads them
back (name -> Field). Building and Torsion are declared so; their constructors' checks
(`checked`), the building files and `--building NAME=VALUE` (pipeline/building_file.py), the
archives' provenance and the docs all read the same declarations.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np

from .errors import EngineError
from .parameters import interval, outside, unit_text

KINDS = ("number", "shorthand", "flag", "text", "law", "component")
"""What a field holds: numbers (one, one per level or story, or (x, y) pairs), a number that
is a law's parameter given directly (the law checks it), True/False, a word among `choices`,
a law (engine.Isolator, engine.Stories) or a component (engine.Torsion)."""
PER = (None, "level", "story", "pair", "point")
"""A number field's shape: None one value; "level" one per level, the isolation slab first;
"story" one per story, the first story first; "pair" one (x, y) pair in metres, or one per
`pairs_per` (level or story); "point" (n, 2) points in metres (one per bearing)."""


@dataclass(frozen=True)
class Field:
    """One declared field of a building component.

    units: UDUNITS string of its SI unit (None: not a number); meaning: one line (the docs' and
    the archives' description); kind: one of KINDS; per: one of PER; pairs_per: for per="pair",
    what else there may be one pair of ("level" or "story"); valid: interval notation of the
    numbers accepted (None: any finite number, or not a number); plausible: interval of the
    values a real building has (checked by the pipeline, not the engine); choices: the words a
    text field takes; optional: None is a value (the field unused or defaulted); equation: the
    clause or equation it follows.
    """

    units: str | None
    meaning: str
    kind: str = "number"
    per: str | None = None
    pairs_per: str | None = None
    valid: str | None = None
    plausible: str | None = None
    choices: tuple[str, ...] = ()
    optional: bool = False
    equation: str = ""

    def __post_init__(self):
        if self.kind not in KINDS or self.per not in PER:
            raise ValueError(f"{self.meaning}: kind must be one of {KINDS} and per one of "
                             f"{PER}, got {self.kind!r}, {self.per!r}")
        for text in (self.valid, self.plausible):
            if text is not None:
                interval(self.meaning, text)

    @property
    def unit_text(self) -> str:
        """The unit in the paper's spelling ('N/m'; '' for a pure number)."""
        return "" if self.units is None else unit_text(self.units)

    @property
    def many(self) -> bool:
        """Whether the field holds one value per level or per story."""
        return self.per in ("level", "story")

    @property
    def coordinates(self) -> bool:
        """Whether the field holds (x, y) coordinates in metres."""
        return self.per in ("pair", "point")


def declared(default, units: str | None, meaning: str, **declaration):
    """A dataclass field with its default and its Field (see Field) in the metadata."""
    return field(default=default, metadata={"declared": Field(units, meaning, **declaration)})


def fields_of(cls) -> dict[str, Field]:
    """name -> Field of every declared field of a dataclass (or instance), in order."""
    return {f.name: f.metadata["declared"] for f in dataclasses.fields(cls)
            if "declared" in f.metadata}


def defaults_of(cls) -> dict:
    """name -> default of every field of a dataclass."""
    return {f.name: f.default for f in dataclasses.fields(cls)}


def checked(name: str, spec: Field, value, count: int | None = None, why: str = ""):
    """A number field's value checked against its declaration and as the frozen dataclass
    keeps it (a float, or a tuple of floats); EngineError naming the field, what it must be
    and the unit. count: the values a per-level or per-story field must have; why: the
    reason for that count, said in the message."""
    unit = f" in {spec.unit_text}" if spec.unit_text else ""
    what = _what(spec)
    if spec.many:
        array = _floats(value)
        if array is None or array.shape != (count,) or _bad(spec, array):
            where = "level" if spec.per == "level" else "story"
            raise EngineError(f"{name} must be {count} {what}{unit} (one per {where}{why}), "
                              f"got {value!r}")
        return tuple(array.tolist())
    array = _floats(value) if not isinstance(value, (bool, np.bool_)) else None
    if array is None or array.shape != () or _bad(spec, array):
        must = "a number" if spec.valid is None else f"in {spec.valid}"
        raise EngineError(f"{name} must be {must}{unit}, got {value!r}")
    return float(array)


def _what(spec: Field) -> str:
    return "positive values" if spec.valid == "(0, inf)" else \
        f"values in {spec.valid}" if spec.valid else "finite values"


def _floats(value) -> np.ndarray | None:
    try:
        return np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        return None


def _bad(spec: Field, array: np.ndarray) -> bool:
    """Whether any value is not finite or outside the declared valid interval."""
    if spec.valid is None:
        return not np.all(np.isfinite(array))
    return bool(np.any(outside(array, interval(spec.meaning, spec.valid))))


def field_table(fields: dict[str, Field], defaults: dict, prefix: str = "") -> str:
    """A component's declared fields as a Markdown table (docs/model.md holds Building's and
    Torsion's; a test keeps them current): name, unit, shape, valid range, default, meaning."""
    shapes = {None: "one", "level": "one per level", "story": "one per story",
              "pair": "(x, y)", "point": "(n, 2)"}
    lines = ["| field | unit | shape | valid | default | meaning |", "|---" * 6 + "|"]
    for name, spec in fields.items():
        shape = shapes[spec.per] + (f" or one per {spec.pairs_per}" if spec.pairs_per else "")
        if spec.kind not in ("number", "shorthand"):
            shape = {"flag": "True / False", "text": " / ".join(spec.choices),
                     "law": "a law", "component": "a component"}[spec.kind]
        default = defaults[name]
        default = "required" if default is None and not spec.optional else \
            f"{default:g}" if isinstance(default, float) else repr(default)
        if len(default) > 24:
            default = "the paper's"
        lines.append(f"| `{prefix}{name}` | {spec.unit_text or '-'} | {shape} | "
                     f"{spec.valid or '-'} | {default} | {spec.meaning} |")
    return "\n".join(lines)
