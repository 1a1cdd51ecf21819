"""Refresh the documentation's gallery (docs/*.png) from the recipes' figures.

Run every recipe at full resolution first (`bumpers NAME` or `python -m studies.NAME`, the
figures land in results/), then from the project root::

    python tools/gallery.py                      # results/*.png -> docs/*.png
    python tools/gallery.py --results DIR --width 1600

Each figure is resized to --width pixels (never enlarged; 1600 keeps the recipes' 7-8 pt text
readable in a browser at full width) with a Lanczos filter and stored as an indexed PNG of 256
colours, which keeps text and lines sharp at a third of the size. Only the figures that
docs/ already shows are refreshed, unless --all.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def refresh(source: Path, target: Path, width: int) -> tuple[int, int]:
    """Write `source` resized to at most `width` pixels wide into `target`; (bytes, width)."""
    from PIL import Image

    with Image.open(source) as image:
        image = image.convert("RGB")
        if image.width > width:
            height = round(image.height * width / image.width)
            image = image.resize((width, height), Image.Resampling.LANCZOS)
        image.quantize(colors=256, method=Image.Quantize.MEDIANCUT).save(target, optimize=True)
        return target.stat().st_size, image.width


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--results", type=Path, default=ROOT / "results",
                   help="folder holding the recipes' full-resolution figures")
    p.add_argument("--docs", type=Path, default=ROOT / "docs")
    p.add_argument("--width", type=int, default=1600, help="largest width in pixels")
    p.add_argument("--all", action="store_true",
                   help="every figure in --results, not only those docs/ already shows")
    args = p.parse_args(argv)
    names = sorted(p.name for p in (args.results if args.all else args.docs).glob("*.png"))
    missing = [name for name in names if not (args.results / name).is_file()]
    if missing:
        print(f"error: not in {args.results}: {', '.join(missing)}; run those recipes first",
              file=sys.stderr)
        return 2
    for name in names:
        size, width = refresh(args.results / name, args.docs / name, args.width)
        print(f"{args.docs / name}: {width} px wide, {size / 1024:.0f} kB")
    return 0


if __name__ == "__main__":
    sys.exit(main())
