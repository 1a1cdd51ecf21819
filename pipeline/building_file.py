"""The user's building from text: a TOML or JSON file, and NAME=VALUE settings on the command
line, into an engine.Building. SI units throughout, each field as engine.building.FIELDS
declares it (a building that twists: its [torsion] table, engine.torsion_fields.FIELDS); a
wrong key, type or unit is one BuildingError naming the key and what it expects.

    # examples/eight_story_friction_pendulum.toml (abridged)
    masses = [600e3, 450e3, 450e3, 450e3, 450e3, 450e3, 450e3, 450e3, 400e3]  # kg, slab first
    story_stiffness = [1.2e9, 1.1e9, 1.0e9, 0.9e9, 0.8e9, 0.7e9, 0.6e9, 0.5e9]  # N/m
    story_yield_force = [8e6, 7.5e6, 7e6, 6.2e6, 5.4e6, 4.4e6, 3.3e6, 2e6]  # N (optional)
    # story_stiffness_y = [...]  # N/m along y in plan (optional, linear stories only)
    # story_height = [4.0, 3.5, 3.5, 3.5, 3.5, 3.5, 3.5, 3.5]  # m (P-Delta, collapse)
    # p_delta = true
    # collapse_drift_ratio = 0.10
    # [stories]             # optional, instead of story_yield_force: a story law
    # law = "imk"           # engine/stories/laws/; each value one number or one per story
    # yield_force = [...]   # N
    # plastic_deformation = 0.09       # m
    # post_capping_deformation = 0.35  # m
    [isolator]              # optional: the bilinear k1, k2, fy_ratio keys otherwise
    law = "friction_pendulum"
    radius = 2.2            # m
    mu_slow = 0.05
    mu_fast = 0.10
    rate = 30.0             # s/m
    # [torsion]             # optional: a building that twists (engine.Torsion)
    # plan_size = [30, 20]  # m
    # mass_offset = [1.5, 0.0]  # m, the mass centre from the plan's centre

Every top-level key is an engine.Building field; the [isolator] table names a registered
isolator law and its declared parameters (engine/isolators/laws/), the [stories] table a
story law and its (engine/stories/laws/), the [torsion] table the fields of engine.Torsion
(on the command line torsion.NAME=VALUE). A JSON file holds the same object.
"""
from __future__ import annotations

import json
import sys
from collections.abc import Sequence
from pathlib import Path

import numpy as np

import engine
from engine.building import FIELDS, MAX_STORIES, PAPER_MASSES
from engine.isolators import LAWS as ISOLATOR_LAWS
from engine.parameters import REQUIRED, Parameter
from engine.stories import LAWS as STORY_LAWS
from engine.torsion_fields import FIELDS as TORSION_FIELDS

from .checks import plausible
from .errors import BuildingError, SweepError

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib


PER_LEVEL = tuple(name for name, spec in FIELDS.items() if spec.per == "level")
PER_STORY = tuple(name for name, spec in FIELDS.items() if spec.per == "story")
TABLES = {name: spec for name, spec in FIELDS.items() if spec.kind in ("law", "component")}
"""The fields given as a table of their own ([isolator], [stories], [torsion])."""
# What real buildings have, per field (SI; the declarations' `plausible`): outside it a value
# is most likely in another unit (t for kg, kN/mm for N/m, kN for N). The engine itself takes
# any positive value, so that a laboratory model can be simulated directly.
PLAUSIBLE = {name: Parameter(name, spec.units, spec.meaning, REQUIRED, spec.valid or
                             "(-inf, inf)", plausible=spec.plausible)
             for name, spec in FIELDS.items() if spec.plausible is not None}


def check_building(building):
    """The paper's engine.Building for None, `building` if it is one, else SweepError; a
    building no real structure is (pipeline.building_file.check_plausible) too."""
    building = engine.Building() if building is None else building
    if not isinstance(building, engine.Building):
        raise SweepError(f"building must be an engine.Building, got {type(building).__name__}")
    check_plausible(building)
    return building


def check_plausible(building: engine.Building) -> None:
    """BuildingError for a level mass, story stiffness or yield force no real building has,
    with the conversion from the unit most likely meant; the isolator's parameters against
    their law's declared plausible ranges."""
    for name, param in PLAUSIBLE.items():
        value = getattr(building, name)
        if value is not None:
            try:
                plausible(name, param, np.asarray(value, float), option=False)
            except SweepError as err:
                raise BuildingError(f"building {err}") from None
    declared = ISOLATOR_LAWS[building.isolation.law].PARAMETERS
    for name, value in building.isolation.parameters:
        try:
            plausible(name, declared[name], np.asarray(value, float), option=False)
        except SweepError as err:
            raise BuildingError(f"building isolator {err}") from None


def read_building(path) -> engine.Building:
    """The engine.Building described by a TOML (.toml) or JSON (.json) file."""
    path = Path(path)
    return building(_read_data(path), where=f"building file {path}")


def _read_data(path: Path) -> dict:
    """The mapping of a TOML or JSON building file, as written."""
    if not path.is_file():
        raise BuildingError(f"building file {path} does not exist")
    try:
        if path.suffix.lower() == ".json":
            data = json.loads(path.read_text())
        elif path.suffix.lower() == ".toml":
            data = tomllib.loads(path.read_text())
        else:
            raise BuildingError(f"building file {path}: give a .toml or .json file")
    except (ValueError, UnicodeDecodeError) as err:  # tomllib.TOMLDecodeError is a ValueError
        raise BuildingError(f"building file {path}: not valid "
                            f"{path.suffix.lstrip('.').upper()}: {err}") from None
    if not isinstance(data, dict):
        raise BuildingError(f"building file {path}: expected a table of building fields")
    return data


def building_from(specs: Sequence[str] = ()) -> engine.Building:
    """The building of a command line's --building options: at most one FILE (TOML or JSON)
    and any NAME=VALUE settings applied over it (or over the paper's building), e.g.
    `masses=320e3,320e3,250e3 story_stiffness=5e8,4e8` (comma lists for per-level and
    per-story fields). A building of another height than the paper's needs its masses and
    story_stiffness both; a field of the user's building left at the paper's value (masses,
    story_stiffness, the isolator) is said in one 'note: ...' line on stderr (the archive's
    building_* attributes record every value)."""
    files = [s for s in specs if "=" not in s]
    if len(files) > 1:
        raise BuildingError(f"--building: one building file at most, got {files}")
    fields, where = {}, "--building"
    if files:
        fields = dict(_read_data(Path(files[0])))
        where = f"building file {files[0]}"
    settings = [s for s in specs if "=" in s]
    if settings:
        where = f"--building (over building file {files[0]})" if files else "--building"
    for setting in settings:
        name, _, text = setting.partition("=")
        name = name.strip()
        table, _, part = name.rpartition(".")
        declarations = TORSION_FIELDS if table == "torsion" else FIELDS if not table else {}
        if part not in declarations or part in TABLES:
            settable = ", ".join([*(n for n in FIELDS if n not in TABLES),
                                  *(f"torsion.{n}" for n in TORSION_FIELDS)])
            raise BuildingError(f"--building {setting!r}: NAME must be one of {settable} (an "
                                "isolator or story law is given in a building file)")
        spec = declarations[part]
        if spec.coordinates:  # x,y pairs, one after the other: "30,20" or "-15,-10;15,10"
            text = [pair.split(",") for pair in text.split(";")]
            text = text[0] if len(text) == 1 and spec.per == "pair" else text
        elif spec.many:
            text = text.split(",")
        value = text if spec.units is None else \
            _numbers(part, spec, text, f"--building {setting!r}")
        if table:
            torsion = fields.setdefault("torsion", {})
            if not isinstance(torsion, dict):
                raise BuildingError(f"--building {setting!r}: the building file's torsion is "
                                    "not a table")
            torsion[part] = value
        else:
            fields[name] = value
    result = building(fields, where=where)
    notice = defaults_notice(fields, where, described=bool(files))
    if notice:
        check_plausible(result)  # an implausible value: one error line, no notice before it
        print(f"note: {notice}", file=sys.stderr)
    return result


def _given(data: dict) -> set:
    """The fields a mapping gives (a JSON null is the field's default: not given)."""
    return {name for name, value in data.items() if value is not None}


def _stories_implied(data: dict) -> dict:
    """field -> the number of stories its length implies, for the per-level and per-story
    fields a mapping gives as lists."""
    implied = {}
    for name in PER_LEVEL + PER_STORY:
        value = data.get(name)
        if isinstance(value, (list, tuple)) and value:
            implied[name] = len(value) - 1 if name in PER_LEVEL else len(value)
    return implied


PAPER_STORIES = len(PAPER_MASSES) - 1
"""The paper's building: 4 stories (5 levels, the isolation slab included)."""


def check_complete(data: dict, where: str) -> None:
    """BuildingError in one line, naming only what the user gave, when the building's height
    differs from the paper's and masses or story_stiffness is not given (the paper's would not
    fit), or masses are given without story_stiffness (the paper's stories belong to the
    paper's masses)."""
    given = _given(data)
    implied = _stories_implied(data)
    other = {name: n for name, n in implied.items() if n != PAPER_STORIES}
    required = ["masses", "story_stiffness"] if other else \
        ["story_stiffness"] if "masses" in given else []
    missing = [name for name in required if name not in given]
    levels = implied.get("masses")
    if not missing or (levels is not None and not 1 <= levels <= MAX_STORIES):
        return  # nothing missing, or masses the engine refuses by themselves
    for name in sorted(given & set(PLAUSIBLE)):  # a unit slip first: it explains the rest
        try:
            plausible(name, PLAUSIBLE[name], np.asarray(data[name], float), option=False)
        except SweepError as err:
            raise BuildingError(f"building {err}") from None
    basis = next(name for name in ("masses", "story_stiffness", *implied) if name in implied) \
        if implied else None
    stories = PAPER_STORIES if basis is None else implied[basis]
    wants = {"masses": f"masses in kg ({stories + 1} values, the isolation slab first)",
             "story_stiffness": f"story_stiffness in N/m ({stories} value"
                                f"{'s' if stories != 1 else ''}, the first story first)"}
    because = "" if basis is None else \
        f", as {basis} gives {stories + 1} levels" if basis in PER_LEVEL else \
        f", as {basis} gives {stories} stor{'ies' if stories != 1 else 'y'}"
    raise BuildingError(f"{where}: {' and '.join(missing)} "
                        f"{'is' if len(missing) == 1 else 'are'} missing: give "
                        + " and ".join(wants[name] for name in missing) + because)


def defaults_notice(data: dict, where: str, described: bool = False) -> str | None:
    """What the user's building takes from the paper's (masses, story_stiffness, the bilinear
    isolator), in one line; None when the user gave no building of their own (no file,
    neither masses nor story_stiffness) or gave all of them."""
    given = _given(data)
    if not (described or given & {"masses", "story_stiffness"}):
        return None
    paper = engine.Building()
    taken = []
    if "masses" not in given:
        taken.append("masses " + ", ".join(map(_engineering, paper.masses)) + " kg")
    if "story_stiffness" not in given:
        taken.append("story_stiffness " + ", ".join(map(_engineering, paper.story_stiffness))
                     + " N/m")
    if "isolator" not in given:
        isolator = [f"{name} {_engineering(getattr(paper, name))}{unit}"
                    for name, unit in (("k1", " N/m"), ("k2", " N/m"), ("fy_ratio", ""))
                    if name not in given]
        if isolator:
            taken.append("bilinear isolator " + ", ".join(isolator))
    if not taken:
        return None
    return (f"{where}: not given, so the paper's {'; '.join(taken)} (recorded in the "
            "archive's building_* attributes)")


def building(data: dict, where: str = "building") -> engine.Building:
    """engine.Building from a mapping of its fields (SI units; an `isolator` mapping with
    `law` and the law's parameters), every value checked by name."""
    unknown = sorted(set(data) - set(FIELDS))
    if unknown:
        raise BuildingError(f"{where}: unknown key(s) {unknown}; a building has "
                            f"{', '.join(FIELDS)}")
    fields = {}
    for name, value in data.items():
        if value is None:  # the field's default (JSON null)
            continue
        spec = FIELDS[name]
        if name in LAW_TABLES:
            fields[name] = value if isinstance(value, LAW_TABLES[name][1]) \
                else _law_table(name, value, where)
        elif name == "torsion":
            fields[name] = value if isinstance(value, engine.Torsion) \
                else _torsion_table(value, where)
        elif spec.kind == "flag":
            fields[name] = _flag(name, value, where)
        elif spec.units is None:
            if not isinstance(value, str):
                raise BuildingError(f"{where}: {name} must be text, got {value!r}")
            fields[name] = value
        else:
            fields[name] = _numbers(name, spec, value, where)
    check_complete(fields, where)
    try:
        return engine.Building(**fields)
    except engine.EngineError as err:
        raise BuildingError(f"{where}: {err}") from None


def _engineering(value: float) -> str:
    """A value as the building files write it: 320e3, 600e6, 0.1."""
    if abs(value) < 1e3:
        return f"{value:g}"
    exponent = int(np.floor(np.log10(abs(value)) / 3) * 3)
    return f"{value / 10 ** exponent:g}e{exponent}"


def _flag(name: str, value, where: str) -> bool:
    """True or False from a TOML/JSON boolean or the command line's text."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    text = str(value).strip().lower()
    if text in ("true", "yes", "1"):
        return True
    if text in ("false", "no", "0"):
        return False
    raise BuildingError(f"{where}: {name} must be true or false, got {value!r}")


LAW_TABLES = {"isolator": (ISOLATOR_LAWS, engine.Isolator, (int, float)),
              "stories": (STORY_LAWS, engine.Stories, (int, float, list, tuple))}
"""A building's law tables: key -> (its registry, the engine type built from it, the types a
parameter may have: a story's value is one number or one per story)."""


def _law_table(key: str, table, where: str):
    """The engine.Isolator or engine.Stories of a [isolator] or [stories] table: law = a name
    of its registry and that law's parameters; BuildingError naming what is wrong."""
    laws, make, types = LAW_TABLES[key]
    if not isinstance(table, dict) or not isinstance(table.get("law"), str):
        raise BuildingError(f"{where}: {key} must be a table with law = one of "
                            f"{', '.join(laws)} and that law's parameters")
    law = table["law"]
    if law not in laws:
        raise BuildingError(f"{where}: {key} law {law!r} is not one of {', '.join(laws)}")
    declaration = laws[law].PARAMETERS
    params = {k: v for k, v in table.items() if k != "law"}
    for name, value in params.items():
        if name in declaration and (isinstance(value, bool) or not isinstance(value, types)):
            raise BuildingError(f"{where}: {key} {name} must be a number in "
                                f"{declaration[name].units}, got {value!r}")
    try:
        return make.of(law, **params)
    except (engine.EngineError, TypeError, ValueError) as err:
        raise BuildingError(f"{where}: {key} ({law}): {err}") from None


def _torsion_table(table, where: str) -> engine.Torsion:
    """The engine.Torsion of a [torsion] table (its declared fields, engine.torsion_fields);
    BuildingError naming what is wrong."""
    if not isinstance(table, dict):
        raise BuildingError(f"{where}: torsion must be a table of {', '.join(TORSION_FIELDS)}")
    unknown = sorted(set(table) - set(TORSION_FIELDS))
    if unknown:
        raise BuildingError(f"{where}: unknown torsion key(s) {unknown}; a building that twists "
                            f"has {', '.join(TORSION_FIELDS)}")
    fields = {name: _numbers(name, TORSION_FIELDS[name], value, where)
              for name, value in table.items() if value is not None}
    try:
        return engine.Torsion(**fields)
    except engine.EngineError as err:
        raise BuildingError(f"{where}: torsion: {err}") from None


def _numbers(name: str, spec, value, where: str):
    """A float, or a tuple of floats for per-level and per-story fields, named in errors with
    the unit the field (its declaration, spec) expects."""
    units = spec.units
    if spec.coordinates:
        return _coordinates(name, spec, value, where)
    many = spec.many
    what = ("a list of numbers, one per level from the isolation slab up" if spec.per == "level"
            else "a list of numbers, one per story from the first up" if many else "a number")
    unit = "" if units == "1" else f" in {units}"
    try:
        if many:
            if isinstance(value, (str, int, float)) or value is None:
                raise TypeError
            return tuple(float(v) for v in value)
        if isinstance(value, (list, tuple, dict)):
            raise TypeError
        return float(value)
    except TypeError:
        raise BuildingError(f"{where}: {name} must be {what}{unit}, got {value!r}") from None
    except ValueError:
        raise BuildingError(f"{where}: {name} must be {what}{unit}: {value!r} is not a "
                            "number") from None


def _coordinates(name: str, spec, value, where: str):
    """An (x, y) pair or a list of them (m), as nested tuples of floats: plan_size,
    mass_offset (one pair, or one per level), isolator_positions (one per bearing)."""
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        array = None
    if array is None or array.ndim not in (1, 2) or array.shape[-1] != 2:
        several = spec.pairs_per or spec.per == "point"
        raise BuildingError(f"{where}: {name} must be an (x, y) pair in m"
                            f"{' or a list of them' if several else ''}, e.g. "
                            f"[30, 20], got {value!r}")
    if array.ndim == 1:
        return tuple(array.tolist())
    return tuple(map(tuple, array.tolist()))

