"""Command line for `pipeline.sweep`: run a parameter grid, write a NetCDF archive.

    python -m studies.sweep --records kobe pacoima --gap-cm 15 30 45 --n-bumpers 4 8 \\
        --baseline --out results/gap.nc

A parameter given one value is held fixed (a scalar coordinate); several values are swept
(a dimension). Errors in the input print one line and exit with status 2.

Not a figure's recipe: the pipeline's general command line, for grids no figure fixes. It lives
in studies/ because studies/ holds every command a user runs, the figures' recipes and this
sweep alike, and they share one set of command-line conventions (_recipe.py: --out as an
archive path or a folder, --records, --records-dir, --workers, --scheduler, --dt, --quiet,
negative numbers as values, the one-line error and the resumable work folder).
"""
from __future__ import annotations

import argparse
import sys

from engine.impact import LAWS, M_EFF
from engine.units import CM, KN_PER_MM
from pipeline.grid import BASELINE, IMPACT_LAWS

from ._recipe import accept_negative_numbers, outputs


def declared(name: str) -> str:
    """What sweep parameter `name` is under each law that takes it: the laws' declarations."""
    parts = []
    for law in IMPACT_LAWS:
        p = LAWS[law].PARAMETERS.swept().get(name)
        if p is not None:
            default = "required" if p.required else f"default {p.default:g}"
            parts.append(f"{law}: {p.meaning}, {p.units}, in {p.valid}, {default}")
    return "; ".join(parts)


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="python -m studies.sweep",
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
    gap = p.add_mutually_exclusive_group(required=True)
    gap.add_argument("--gap", nargs="+", type=float, metavar="M",
                     help="seismic gap between base slab and moat wall, before bumpers, m "
                          "(with bumpers the clear gap is gap - thickness)")
    gap.add_argument("--gap-cm", nargs="+", type=float, metavar="CM", help="the gap in cm")
    thickness = p.add_mutually_exclusive_group()
    thickness.add_argument("--thickness", nargs="+", type=float, metavar="M",
                           help=declared("thickness"))
    thickness.add_argument("--thickness-cm", nargs="+", type=float, metavar="CM",
                           help="bumper thickness in cm")
    cavity = p.add_mutually_exclusive_group()
    cavity.add_argument("--cavity", nargs="+", type=float, metavar="M",
                        help=declared("cavity"))
    cavity.add_argument("--cavity-cm", nargs="+", type=float, metavar="CM",
                        help="cavity depth in cm")
    p.add_argument("--strain", nargs="+", type=float, metavar="EPS",
                   help=declared("strain"))
    p.add_argument("--n-bumpers", nargs="+", type=int, metavar="N",
                   help=declared("n_bumpers"))
    wall = p.add_mutually_exclusive_group()
    wall.add_argument("--wall-k", nargs="+", type=float, metavar="K",
                      help="wall stiffness, per law: " + declared("wall_k"))
    wall.add_argument("--wall-k-kn-mm", nargs="+", type=float, metavar="K",
                      help="wall stiffness in kN/mm (bumper and linear laws only)")
    p.add_argument("--cor", nargs="+", type=float, metavar="E",
                   help=declared("cor"))
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
    p.add_argument("--m-eff", type=float, default=M_EFF.default, metavar="KG",
                   help=f"{M_EFF.meaning}, kg (default: {M_EFF.default:g})")
    p.add_argument("--damping", choices=("paper", "modal"), default="paper",
                   help="building damping model, see engine.Building (default: paper)")
    p.add_argument("--dt", type=float, metavar="S",
                   help="integration step, s (default: engine.DEFAULT_DT); refused above the "
                        "stability limit")
    p.add_argument("--workers", type=int, default=1,
                   help="1 (default): in this process, the compiled kernel on every core "
                        "through threads; N >= 2: N local dask worker processes, one thread "
                        "each")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="dask.distributed scheduler to run on, e.g. tcp://host:8786 (instead "
                        "of a local cluster)")
    p.add_argument("--batch-size", type=int, metavar="N",
                   help="simulations per engine call (default: up to 512)")
    p.add_argument("--out", default="results", metavar="PATH",
                   help="where the archive goes, as for every recipe: a path ending in .nc is "
                        "the archive itself (.zarr: a Zarr store, for large sweeps), anything "
                        "else a folder receiving sweep.nc "
                        "(default: results/); finished simulations wait in <archive>.work/ "
                        "until it is written, so an interrupted run resumes where it stopped")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    accept_negative_numbers(p)
    return p


def _one_or_many(values, scale: float = 1.0):
    """None, a scalar (one value: held fixed) or a list (several: swept), times scale."""
    if values is None:
        return None
    values = [v * scale for v in values]
    return values[0] if len(values) == 1 else values


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    import engine
    import pipeline
    from pipeline.errors import Interrupted, SweepError

    from ._recipe import announce_stand_ins

    try:
        if args.wall_k_kn_mm is not None and args.impact not in ("bumper", "linear"):
            raise SweepError(f"wall_k: --wall-k-kn-mm is for N/m stiffnesses (bumper, linear); "
                             f"give --wall-k in N/m^1.5 for impact={args.impact!r}")
        building = engine.Building(damping=args.damping)
        archive, _ = outputs(args.out, "sweep", archives=(".nc", ".zarr"))
        with announce_stand_ins():
            ds = pipeline.sweep(
                records=args.records,
                gap=_one_or_many(args.gap) if args.gap else _one_or_many(args.gap_cm, CM),
                thickness=_one_or_many(args.thickness) if args.thickness
                else _one_or_many(args.thickness_cm, CM),
                cavity=_one_or_many(args.cavity) if args.cavity
                else _one_or_many(args.cavity_cm, CM),
                strain=_one_or_many(args.strain),
                n_bumpers=_one_or_many(args.n_bumpers),
                wall_k=_one_or_many(args.wall_k) if args.wall_k
                else _one_or_many(args.wall_k_kn_mm, KN_PER_MM),
                cor=_one_or_many(args.cor), impact=args.impact, dt=args.dt, workers=args.workers,
                scheduler=args.scheduler, out=archive, baseline=args.baseline,
                unconstrained=args.unconstrained, building=building, m_eff=args.m_eff,
                batch_size=args.batch_size, records_dir=args.records_dir, quiet=args.quiet)
    except (SweepError, engine.EngineError) as err:
        print("error: " + " ".join(str(err).split()), file=sys.stderr)  # one line
        return 2
    except Interrupted as stop:
        print(f"sweep: {stop}; run the same command again to resume", file=sys.stderr)
        return 130
    except KeyboardInterrupt:
        print("sweep: interrupted", file=sys.stderr)
        return 130
    dims = ", ".join(f"{d} {n}" for d, n in ds.sizes.items())
    print(f"wrote {archive} ({dims})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
