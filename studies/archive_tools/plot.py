"""`bumpers plot ARCHIVE --x DIM [--y PEAK]`: a peak of a sweep's archive against one of its
swept dimensions.

    bumpers plot results/my_sweep.nc --x gap
    bumpers plot results/my_sweep.nc --x gap --y peak_interstory_drift --story 1

The peak (default peak_total_accel: the largest over the floors, in g) is drawn against --x,
one line per combination of the other dimensions it runs over (record, the other swept
parameters) when there are at most MAX_LINES of them, else their median with the 16-84%
band; the axes are labelled with the archive's long names and units (accelerations in g, the
project's g of engine.units). A peak along floors or stories is their largest unless --floor or
--story picks one. Unknown dimensions or peaks are refused in one line listing those there
are; the figure is written to a temporary file and renamed (pipeline.writing.Staged).
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from ..common.recipe import OneLineParser
from .table import BLOCKS, TRAILING, ArchiveError, open_archive, run_dims, select

MAX_LINES = 6
"""More combinations of the other dimensions than this: their median and 16-84% band."""
BAND = (0.16, 0.84)
"""The quantiles of the band."""


def parser() -> argparse.ArgumentParser:
    p = OneLineParser(
        prog="bumpers plot",
        description="Draw a peak of a sweep archive (pipeline.sweep or `bumpers sweep`, "
                    "NetCDF or Zarr) against one of its swept dimensions: one line per value "
                    f"of the others (at most {MAX_LINES} lines, else their median and 16-84% "
                    "band).")
    p.add_argument("archive", metavar="ARCHIVE", help="the sweep's archive (.nc or .zarr)")
    p.add_argument("--x", required=True, metavar="DIM",
                   help="the swept dimension along the x axis (gap, n_bumpers, record, ...)")
    p.add_argument("--y", default="peak_total_accel", metavar="PEAK",
                   help="the archive variable drawn (default peak_total_accel: the largest "
                        "peak floor acceleration over the floors, in g); a baseline_ or "
                        "unconstrained_ variable draws that block")
    level = p.add_mutually_exclusive_group()
    level.add_argument("--floor", type=int, metavar="N",
                       help="this floor instead of the largest over the floors (0: isolation "
                            "level)")
    level.add_argument("--story", type=int, metavar="N",
                       help="this story instead of the largest over the stories")
    p.add_argument("--sel", action="append", default=[], metavar="DIM=VALUE",
                   help="hold a swept dimension at one value, e.g. --sel n_bumpers=8 "
                        "(repeatable)")
    p.add_argument("--out", metavar="FIG.png",
                   help="the figure (.png, .pdf or .svg; default: beside the archive, "
                        "ARCHIVE-STEM_PEAK_vs_DIM.png)")
    return p


def peaks(ds) -> list[str]:
    """The archive's variables a plot can draw: every per-run result of every block."""
    return [name for name, var in ds.data_vars.items()
            if var.dims[:1] == ("record",) and var.dtype.kind in "fiub"
            and any(name.startswith(p) for p in BLOCKS)]


def curve(ds, args):
    """(values along (x, others...) as a DataArray, y label) of the chosen peak: reduced over
    its trailing axes, acceleration in g."""
    from engine.units import G

    if args.y not in peaks(ds):
        raise ArchiveError(f"--y {args.y}: no such peak; the archive has {', '.join(peaks(ds))}")
    var = ds[args.y]
    if args.x not in run_dims(var):
        dims = [d for d in ds.dims if d not in TRAILING]
        raise ArchiveError(f"--x {args.x}: {args.y} does not run over it; its dimensions are "
                           f"{', '.join(run_dims(var)) or 'none'} (the archive's: "
                           f"{', '.join(dims)})")
    units, name = var.attrs.get("units", "1"), var.attrs.get("long_name", args.y)
    for axis, chosen in (("floor", args.floor), ("story", args.story)):
        if chosen is not None and axis not in var.dims:
            raise ArchiveError(f"--{axis}: {args.y} is not along {axis}s")
        if axis in var.dims:
            if chosen is None:
                var, name = var.max(axis), f"largest {name} over the {axis}s"
            elif chosen not in var[axis].values:
                raise ArchiveError(f"--{axis} {chosen}: the archive has {axis}s "
                                   f"{', '.join(str(v) for v in var[axis].values)}")
            else:
                var, name = var.sel({axis: chosen}), f"{name}, {axis} {chosen}"
    for axis in ("wall", "direction"):
        if axis in var.dims:
            var, name = var.max(axis), f"{name} (largest over the {axis}s)"
    if units == "m s-2":
        var, units = var / G, "g"
    var = var.astype(float)
    var = var.squeeze([d for d in var.dims if d != args.x and var.sizes[d] == 1], drop=True)
    return var.transpose(args.x, ...), name if units == "1" else f"{name} [{units}]"


def figure(ds, args):
    """The figure: the peak against --x, one line per combination of the other dimensions,
    or their median and band."""
    from ..common.plot import plt

    values, ylabel = curve(ds, args)
    x = ds[args.x]
    xs = x.values
    others = [d for d in values.dims if d != args.x]
    fig, ax = plt.subplots(figsize=(6.4, 4.2), layout="constrained")
    flat = values.values.reshape(len(xs), -1)
    if flat.shape[1] <= MAX_LINES:
        for j in range(flat.shape[1]):
            index = np.unravel_index(j, [values.sizes[d] for d in others]) if others else ()
            text = ", ".join(f"{d} {_value(values[d].values[i])}"
                             for d, i in zip(others, index, strict=True))
            ax.plot(xs, flat[:, j], marker="o", label=text or None)
        if others:
            ax.legend(fontsize="small")
    else:
        low, mid, high = np.nanquantile(flat, [BAND[0], 0.5, BAND[1]], axis=1)
        ax.fill_between(xs, low, high, alpha=0.3,
                        label=f"{BAND[0]:.0%}-{BAND[1]:.0%} over {', '.join(others)}")
        ax.plot(xs, mid, marker="o", label=f"median over {', '.join(others)} "
                                           f"({flat.shape[1]} runs each)")
        ax.legend(fontsize="small")
    xunits = x.attrs.get("units", "1")
    xname = x.attrs.get("long_name", args.x)
    ax.set_xlabel(xname if xunits == "1" else f"{xname} [{xunits}]")
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3)
    return fig


def _value(v) -> str:
    return f"{v:g}" if isinstance(v, (float, np.floating)) else str(v)


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    from pipeline.errors import SweepError
    from pipeline.writing import Staged, check_out

    out = Path(args.out) if args.out else \
        Path(args.archive).with_name(f"{Path(args.archive).stem}_{args.y}_vs_{args.x}.png")
    try:
        if out.suffix.lower() not in (".png", ".pdf", ".svg"):
            raise ArchiveError(f"--out {out}: give a figure name ending in .png, .pdf or .svg")
        check_out(out)
        ds = select(open_archive(args.archive), args.sel)
        fig = figure(ds, args)
        with Staged() as stage:
            fig.savefig(stage.path(out), format=out.suffix[1:].lower(), dpi=150)
            stage.commit()
    except (ArchiveError, SweepError) as err:
        print("error: " + " ".join(str(err).split()), file=sys.stderr)
        return 2
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
