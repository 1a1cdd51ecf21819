"""The command line, ``python -m pipeline.records``: where the paper's records are found, then
the embedded library (:func:`main`); ``--show NAME ...`` says what records and pairs given by
name resolve to (files of ``--records-dir`` first), without running anything."""

from __future__ import annotations

import argparse
import os
import re
import sys

from .library import SETS, library_index, list_records
from .paper import PAPER_RECORDS, paper_records
from .record import RECORDS_DIR_ENV, RecordError


def main(argv: list[str] | None = None) -> int:
    """``python -m pipeline.records``: the paper's records first, then the library listing."""
    parser = argparse.ArgumentParser(
        allow_abbrev=False,  # an option by its whole name only, as the recipes'
        # `bumpers records` names itself so (studies/cli.py sets BUMPERS_PROGRAM)
        prog=os.environ.get("BUMPERS_PROGRAM") or "python -m pipeline.records",
        description="Where the paper's records are found (records directory, built-in data, "
                    "library or stand-in), then the embedded ground-motion library.")
    parser.add_argument("--records-dir", help=f"folder of AT2 files (default: ${RECORDS_DIR_ENV})")
    parser.add_argument("--paper-only", action="store_true",
                        help="list the paper's records only, not the library")
    parser.add_argument("--set", choices=SETS, dest="record_set", help="library set to list")
    parser.add_argument("--event", help="event name substring (case-insensitive)")
    parser.add_argument("--pga-min", type=float, help="lowest PGA to list, g")
    parser.add_argument("--pga-max", type=float, help="highest PGA to list, g")
    parser.add_argument("--show", nargs="+", metavar="NAME",
                        help="say what each record or pair resolves to and stop: a pair "
                             "RSN<n> or A+B, a record RSN<n>:<component>, a paper key, a "
                             "library name or an AT2 file (found in --records-dir first)")
    args = parser.parse_args(argv)
    if args.show:
        return show(args.show, args.records_dir)
    filters = (args.record_set, args.event, args.pga_min, args.pga_max)
    if args.paper_only and any(f is not None for f in filters):
        parser.error("--set, --event, --pga-min and --pga-max filter the library listing, "
                     "which --paper-only leaves out")
    try:
        papers = paper_records(args.records_dir)
        entries = [] if args.paper_only else list_records(*filters)
    except RecordError as exc:
        parser.error(str(exc))
    print("The paper's records (Table 1):")
    print(f"{'paper key':17} {'found in':12} {'record':40} {'PGA g':>6} {'paper':>6} "
          f"{'dt s':>7} {'dur s':>7}")
    for key, rec in zip(PAPER_RECORDS, papers, strict=True):
        print(f"{key:17} {rec.found_in:12} {rec.name:40} {rec.pga_g:6.3f} "
              f"{PAPER_RECORDS[key].pga_g:6.3f} {rec.dt:7.4f} {rec.duration:7.2f}")
    for key, rec in zip(PAPER_RECORDS, papers, strict=True):
        print(f"  {key}: {rec.note}")
    if args.paper_only:
        return 0
    print("\nThe embedded library:")
    print(f"{'name':46} {'selector':13} {'set':19} {'PGA g':>6} {'dt s':>7} {'dur s':>7}")
    for e in entries:
        print(f"{e.name:46} {e.selector:13} {e.set:19} {e.pga_g:6.3f} {e.dt:7.4f} "
              f"{e.duration:7.2f}")
    print(f"({len(entries)} of {len(library_index())} library records)")
    return 0


_PAIR_RE = re.compile(r"^\s*RSN\s*\d+\s*$", re.IGNORECASE)


def show(names: list[str], records_dir=None) -> int:
    """``--show``: one line per component of each name (a pair: RSN<n> or A+B; else one
    record): its file or library name, component, where it was found, step, length and PGA.
    A name that does not resolve is one 'error: ...' line on stderr and exit status 2."""
    from .lookup import load_record
    from .pair import load_pair

    for name in names:
        try:
            if "+" in name or _PAIR_RE.match(name):
                parts = zip(("x", "y"), load_pair(name, records_dir), strict=True)
            else:
                parts = [("record", load_record(name, records_dir))]
        except RecordError as err:
            print("error: " + " ".join(str(err).split()), file=sys.stderr)
            return 2
        for role, rec in parts:
            print(f"{name}: {role} = {rec.name} (component {rec.component}, "
                  f"{rec.found_in or 'given'}: {rec.source}), dt {rec.dt:g} s, "
                  f"{rec.npts} samples, PGA {rec.pga_g:.3f} g")
    return 0
