"""Command line for `pipeline.sweep`: run a parameter grid, write a NetCDF archive.

    python -m studies.sweep --records kobe pacoima --gap-cm 15 30 45 --n-bumpers 4 8 \\
        --baseline --out results/gap.nc

A parameter given one value is held fixed (a scalar coordinate); several values are swept
(a dimension). Errors in the input print one line and exit with status 2.

Not a figure's recipe: the pipeline's general command line, for grids no figure fixes. It lives
in studies/ because studies/ holds every command a user runs, the figures' recipes and this
sweep alike, and they share one set of command-line conventions (common/recipe.py: --out as an
archive path or a folder, --records, --records-dir, --workers, --scheduler, --dt, --quiet,
negative numbers as values, the one-line error and the resumable work folder).
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from engine import DEFAULT_DT
from engine.impact import M_EFF
from engine.units import CM, KN_PER_MM
from pipeline.cluster import add_tls_options
from pipeline.grid import BASELINE
from pipeline.members import (
    EXCITATION_PARAMS,
    IMPACT_LAWS,
    ISOLATOR_PARAMS,
    PARAMS,
    PLAN_PARAMS,
    TORSION_PARAMS,
    declarations,
)

from .common.options import add_backend
from .common.program import program
from .common.recipe import (
    OneLineParser,
    accept_negative_numbers,
    add_text_record_options,
    interrupted,
    outputs,
)

# Units the command line also takes in the paper's units, by the SI unit declared: the option
# --NAME-<suffix> takes values in that unit.
PAPER_UNITS = {"m": ("cm", "CM", CM, "cm"), "N m-1": ("kn-mm", "K", KN_PER_MM, "kN/mm")}
METAVARS = {"m": "M", "1": "X", "degree": "DEG"}


def declared(name: str) -> str:
    """What sweep parameter `name` is under each law that takes it: the laws' declarations
    (once when every law declares it alike, as the gap)."""
    texts = {}
    for law, p in declarations(name).items():
        default = "default: the building's" if name in ISOLATOR_PARAMS else \
            "required" if p.required else f"default {p.default:g}"
        if name in PLAN_PARAMS:
            default += "; runs in plan only (--moat)"
        elif name in TORSION_PARAMS:
            default += ("; a building that twists only (--building torsion.plan_size=BX,BY, --moat "
                        "rectangular)")
        texts[law] = f"{p.help_text()}, in {p.valid}, {default}"
    if len(set(texts.values())) == 1:
        return next(iter(texts.values()))
    return "per law: " + "; ".join(f"{law}: {text}" for law, text in texts.items())


def paper_unit(name: str):
    """(option suffix, metavar, SI value of one unit, unit text, laws) of the paper-unit
    variant of sweep parameter `name`, or None: the laws are those declaring it in the matching
    SI unit. An isolator's lengths (a pendulum's radius, its yield displacement) have none:
    the paper gives them in no other unit."""
    params = declarations(name)
    for si, (suffix, metavar, factor, text) in PAPER_UNITS.items():
        if name in ISOLATOR_PARAMS and si == "m":
            continue
        laws = [law for law, p in params.items() if p.units == si]
        if laws:
            return suffix, metavar, factor, text, laws
    return None


def add_parameters(p: argparse.ArgumentParser) -> None:
    """One option per sweep parameter (pipeline.members.PARAMS, ISOLATOR_PARAMS and
    EXCITATION_PARAMS, from their declarations), with a paper-unit variant (-cm, -kn-mm) where
    one applies."""
    isolator = p.add_argument_group(
        "the isolator's parameters", "replace the building's own values, fixed or swept alike; "
        "each applies to the isolator law that declares it (the building's)")
    for name in (*PARAMS, *ISOLATOR_PARAMS, *EXCITATION_PARAMS):
        p = isolator if name in ISOLATOR_PARAMS else p
        params = declarations(name)
        first = next(iter(params.values()))
        required = name in PARAMS and all(q.required for q in params.values())
        variant = paper_unit(name)
        group = p.add_mutually_exclusive_group(required=required) if variant else p
        option = "--" + name.replace("_", "-")
        group.add_argument(option, nargs="+", type=int if first.integer else float,
                           required=required and not variant,
                           metavar="N" if first.integer else METAVARS.get(first.units, "K"),
                           help=declared(name))
        if variant:
            suffix, metavar, _, text, laws = variant
            only = "" if len(laws) == len(params) else f" ({', '.join(laws)} only)"
            group.add_argument(f"{option}-{suffix}", nargs="+", type=float, metavar=metavar,
                               help=f"{name} in {text}{only}")


def parser() -> argparse.ArgumentParser:
    p = OneLineParser(
        prog=program("studies.sweep"),
        description="Simulate the isolated building pounding on its moat wall for every "
                    "combination of the given parameters and records, and write the peak "
                    "responses to a NetCDF archive. One value holds a parameter fixed, several "
                    "values sweep it. Parameters left out take the impact law's defaults.")
    p.add_argument("--records", nargs="+", required=True, metavar="NAME",
                   help="paper keys (kobe, sylmar_converter, olive_view, pacoima), library "
                        "names, RSN<n>:<component> selectors or AT2 file paths")
    p.add_argument("--records-dir", metavar="DIR",
                   help="folder of AT2 files searched for the paper's records "
                        "(default: $BUMPERS_RECORDS_DIR)")
    add_text_record_options(p)
    add_parameters(p)
    p.add_argument("--moat", choices=("rectangular", "circular"), default=None,
                   help="run in plan: --records are then record PAIRS (RSN<n>, a paper key, "
                        "or A.AT2+B.AT2: two components of one recording), the building moves "
                        "in x and y against a square (rectangular) or circular moat with the "
                        "same walls on every side, --angle rotates the pairs (default: the "
                        "paper's planar model)")
    p.add_argument("--bumpers-along-x", nargs="+", type=float, default=None, metavar="M",
                   help="a building that twists (--building torsion.plan_size=BX,BY): the bumpers' "
                        "positions (m, from the plan's centre, along y) on the two walls normal "
                        "to x, each carrying its share of the wall's law (default: the slab's "
                        "corners meet bare walls); with --bumpers-along-y")
    p.add_argument("--bumpers-along-y", nargs="+", type=float, default=None, metavar="M",
                   help="the bumpers' positions (m, along x) on the two walls normal to y")
    p.add_argument("--impact", default="bumper",
                   choices=IMPACT_LAWS,
                   help="impact law at the moat wall (default: bumper)")
    p.add_argument("--baseline", action="store_true",
                   help="also run the bare wall without bumpers (the linear law at its "
                        f"defaults, wall_k {BASELINE['wall_k'] / KN_PER_MM:g} kN/mm, cor "
                        f"{BASELINE['cor']:g}) at each full gap, and store the amplification "
                        "ratios bumpers / no bumpers (bumper law only)")
    p.add_argument("--unconstrained", action="store_true",
                   help="also run each record without moat wall")
    mass = p.add_mutually_exclusive_group()
    mass.add_argument("--m-eff", type=float, default=None, metavar="KG",
                      help=f"{M_EFF.help_text()} (default: {M_EFF.default:g})")
    mass.add_argument("--m-eff-t", type=float, default=None, metavar="T",
                      help="m_eff in t")
    p.add_argument("--building", action="append", default=[], metavar="FILE|NAME=VALUE",
                   help="the building: a TOML or JSON file (see examples/) and/or "
                        "its fields as NAME=VALUE in SI units, e.g. zeta_sup=0.03, or "
                        "masses=500e3,400e3,300e3 with story_stiffness=9e8,8e8 (repeatable; "
                        "default: the paper's building)")
    p.add_argument("--damping", choices=("paper", "modal"), default=None,
                   help="building damping model: paper (an isolation dashpot plus "
                        "stiffness-proportional story dashpots) or modal (classical damping: "
                        "zeta_iso in the first mode, zeta_sup in the others) (default: the "
                        "building's, paper)")
    p.add_argument("--dt", type=float, metavar="S",
                   help=f"integration step, s (default: {DEFAULT_DT * 1e3:g} ms, converged "
                        "for the paper's runs); refused above the stability limit")
    p.add_argument("--workers", type=int, default=1,
                   help="1 (default): in this process, the compiled kernel on every core "
                        "through threads; N >= 2: N local dask worker processes, one thread "
                        "each")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="dask.distributed scheduler to run on, e.g. tcp://host:8786 (instead "
                        "of a local cluster); tls://host:8786 with the --tls-* options")
    add_tls_options(p)
    p.add_argument("--batch-size", type=int, metavar="N",
                   help="simulations per engine call (default: sized for the cores and the "
                        "records, at most 4096; with --backend cuda, 2^20)")
    add_backend(p)
    p.add_argument("--history", action="append", default=[], metavar="NAME=VALUE[,...]",
                   help="also keep the time histories of one configuration, its wall "
                        "parameters in SI units (e.g. gap=0.2,n_bumpers=8; --impact's law, the "
                        "others at their defaults), under every record: written to "
                        "<archive>.histories.nc beside the archive (pipeline.histories, in "
                        "this process once the sweep is written: a few configurations, one "
                        "engine call a record, run again in full rather than resumed; planar "
                        "sweeps; repeatable)")
    p.add_argument("--out", default="results", metavar="PATH",
                   help="where the archive goes, as for every recipe: a path ending in .nc is "
                        "the archive itself (.zarr: a Zarr store, for large sweeps), anything "
                        "else a folder receiving sweep.nc "
                        "(default: results/); finished simulations wait in <archive>.work/ "
                        "until it is written, so an interrupted run resumes where it stopped")
    p.add_argument("--force", action="store_true",
                   help="replace an existing archive of another sweep (without it, such an "
                        "archive is kept and the run refused before any compute; the same "
                        "sweep is replaced silently)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    accept_negative_numbers(p)
    return p


def _one_or_many(values, scale: float = 1.0):
    """None, a scalar (one value: held fixed) or a list (several: swept), times scale."""
    if values is None:
        return None
    values = [v * scale for v in values]
    return values[0] if len(values) == 1 else values


def parameters(args) -> dict:
    """Sweep parameter -> None, a scalar or a list in SI units, from the options (those in
    paper units converted); SweepError for a paper unit the chosen law does not use."""
    from pipeline.errors import SweepError

    values = {}
    for name in (*PARAMS, *ISOLATOR_PARAMS, *EXCITATION_PARAMS):
        values[name] = _one_or_many(getattr(args, name))
        variant = paper_unit(name)
        given = getattr(args, f"{name}_{variant[0].replace('-', '_')}", None) if variant \
            else None
        if given is not None:
            suffix, _, factor, _, laws = variant
            if name in PARAMS and args.impact not in laws:
                unit = declarations(name)[args.impact].units
                raise SweepError(f"{name}: --{name.replace('_', '-')}-{suffix} is for the "
                                 f"{', '.join(laws)} laws; give --{name.replace('_', '-')} "
                                 f"in {unit} for impact={args.impact!r}")
            values[name] = _one_or_many(given, factor)
            _plausible_in_paper_unit(name, args, given, variant)
    return values


TYPED_PLAUSIBLE = {"gap": "[0.01, 2]"}
"""What a value typed in the paper's unit may be (m) where the law's plausible range is wider:
the studies compute gaps of a few millimetres from weak records' peaks (the law allows any
positive gap), but a moat gap typed under 1 cm is a unit slip (--gap-cm 0.2 meant 20 cm)."""


def _plausible_in_paper_unit(name: str, args, given, variant) -> None:
    """SweepError for a value given in the paper's unit (--gap-cm, --wall-k-kn-mm) that no
    real moat or bumper has, saying what it is in SI and, when the number typed is plausible
    in SI, the option that was most likely meant (a value in m typed after --gap-cm)."""
    import dataclasses

    from pipeline.errors import SweepError

    suffix, _, factor, text, _ = variant
    params = declarations(name)
    param = params.get(args.impact, next(iter(params.values())))
    if name in TYPED_PLAUSIBLE:
        param = dataclasses.replace(param, plausible=TYPED_PLAUSIBLE[name])
    si = np.atleast_1d(np.asarray(given, dtype=float)) * factor
    bad = param.implausible(si)
    if bad.size == 0:
        return
    typed = float(bad[0]) / factor
    option = f"--{name.replace('_', '-')}-{suffix}"
    meant = "" if param.implausible([typed]).size else \
        f"; did you mean {option} {typed / factor:g} ({typed:g} {param.units})?"
    raise SweepError(f"{option} {typed:g} {text} is {float(bad[0]):g} {param.units}, "
                     f"implausible for {name} (outside {param.plausible} {param.units}){meant}")


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    import engine
    import pipeline
    from pipeline.building_file import building_from
    from pipeline.cluster import apply_tls_options
    from pipeline.errors import SweepError, said
    from pipeline.records import RecordError
    from pipeline.records.lookup import read_text_records

    from .common.recipe import announce_stand_ins

    archive = None
    try:
        apply_tls_options(args)
        damping = [] if args.damping is None else [f"damping={args.damping}"]
        building = building_from([*args.building, *damping])
        archive, _ = outputs(args.out, "sweep")
        with announce_stand_ins():
            records = args.records
            if args.moat is None:
                records = read_text_records(records, args.record_units, args.record_dt,
                                            args.records_dir)
            elif args.record_units is not None or args.record_dt is not None:
                raise SweepError("--record-units and --record-dt: text records in plan are "
                                 "not supported yet; give AT2 pairs or library pairs")
            along = (args.bumpers_along_x, args.bumpers_along_y)
            if (along[0] is None) != (along[1] is None):
                raise SweepError("--bumpers-along-x and --bumpers-along-y go together: the "
                                 "bumpers' positions on the x walls and on the y walls")
            m_eff = args.m_eff if args.m_eff_t is None else args.m_eff_t * 1e3
            chosen = history_configurations(args.history, args.impact, args.moat, m_eff)
            ds = pipeline.sweep(
                records=records, moat=args.moat,
                bumper_positions=None if along[0] is None else along,
                **parameters(args),
                impact=args.impact, dt=args.dt, workers=args.workers,
                scheduler=args.scheduler, out=archive, baseline=args.baseline,
                unconstrained=args.unconstrained, building=building,
                m_eff=m_eff, batch_size=args.batch_size, records_dir=args.records_dir,
                quiet=args.quiet, force=args.force, backend=args.backend)
            if chosen:
                kept = write_histories(records, chosen, archive, args, (building, m_eff))
    except (SweepError, RecordError, engine.EngineError) as err:
        print("error: " + said(err), file=sys.stderr)  # one line
        return 2
    except KeyboardInterrupt as stop:
        work = None if archive is None or archive.suffix == ".zarr" \
            else archive.with_name(archive.name + ".work")
        print(f"sweep: {interrupted(stop, work)}", file=sys.stderr)
        return 130
    dims = ", ".join(f"{d} {n}" for d, n in ds.sizes.items())
    print(f"wrote {archive} ({dims})")
    if chosen:
        print(f"wrote {kept} (the time histories of {'; '.join(chosen)})")
    return 0


def history_configurations(given: list[str], impact: str, moat, m_eff) -> dict:
    """--history's configurations, name -> pipeline.histories' parameters (--impact's law),
    checked before any compute: SweepError, one line, for a malformed one, an unknown or
    implausible parameter, or a sweep in plan (pipeline.histories runs the planar model)."""
    from pipeline.errors import SweepError
    from pipeline.histories import configuration_grid

    if not given:
        return {}
    if moat is not None:
        raise SweepError("--history keeps the time histories of planar sweeps; in plan, use "
                         "engine.simulate(..., history=engine.History(...)) from Python")
    chosen = {}
    for text in given:
        config = {"impact": impact}
        for part in text.split(","):
            name, sep, value = part.partition("=")
            try:
                config[name.strip()] = float(value)
            except ValueError:
                raise SweepError(f"--history {text}: give NAME=VALUE[,NAME=VALUE...] in SI "
                                 f"units, e.g. gap=0.2,n_bumpers=8") from None
            if not sep:
                raise SweepError(f"--history {text}: give NAME=VALUE[,NAME=VALUE...]")
        chosen[text] = config
    configuration_grid(chosen, M_EFF.default if m_eff is None else m_eff)  # as the sweep's
    return chosen


def write_histories(records, chosen: dict, archive, args, model) -> Path:
    """The time histories of --history's configurations under every record (pipeline.
    histories, one engine batch a record), written beside the archive; its path."""
    from pipeline.archive import write_netcdf
    from pipeline.histories import concat_records, histories

    building, m_eff = model
    parts = [histories(record, chosen, dt=args.dt, records_dir=args.records_dir,
                       building=building, m_eff=m_eff, quiet=args.quiet)
             for record in records]
    path = archive.with_name(archive.stem + ".histories.nc")
    write_netcdf(concat_records(parts), path)
    return path


if __name__ == "__main__":
    sys.exit(main())
