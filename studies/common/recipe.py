"""What every recipe shares: its command line, the archive, the figure, the paper check.

A recipe module declares a `Recipe` (its grid in `compute`, its figure in `plot`, its check of
the paper's conclusions in `check`) and ends with `main = recipe.main`. Running it:
    compute (or, with --replot, reopen the archive) -> check -> NAME.nc -> NAME.png / .pdf
No physics here: grids go to pipeline.sweep or engine.two_body, peaks come back labelled.

The check returns one `Verdict` per conclusion of the paper the figure covers. The archive
keeps them twice: as prose (attribute `paper_check`) and for scripts (attribute
`paper_verdicts`, a JSON list of {conclusion, claim, finding, verdict, numbers}), e.g.
    json.loads(xr.open_dataset("results/gap_size.nc").attrs["paper_verdicts"])
"""
from __future__ import annotations

import argparse
import json
import sys
import warnings
from collections.abc import Callable
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

from pipeline.cluster import add_tls_options
from pipeline.records import FEMA_SETS, PAPER_KEYS


class OneLineParser(argparse.ArgumentParser):
    """An argparse parser whose errors are one line (argparse prints the whole usage first:
    26 lines for a recipe), exit status 2 as argparse's; an option is taken by its whole name
    only (argparse's prefix matching took `--records kobe` for `--records-dir kobe` in a recipe
    without --records, and ran)."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, allow_abbrev=False, **kwargs)

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message} (--help lists the options)\n")


BEYOND_THE_PAPER = "beyond the paper"
"""A recipe's `figure` where the paper has none (its help then says so, not "paper ...")."""


@dataclass(frozen=True)
class Recipe:
    """name: module and file stem; figure: the paper's figure(s), or BEYOND_THE_PAPER; summary:
        one line for --help; chosen: values the paper does not state, and what was chosen (shown in
        --help, stored in the archive); records: the paper's records for this figure (None: no
        records, e.g. the two-body studies); compute(args) -> Dataset; plot(ds) -> matplotlib
        Figure; check(ds) -> list of Verdict, one per conclusion of the paper against what was
        computed; options(parser): adds the recipe's own command-line options (None: none);
        not_resumable: "" when its simulations go through pipeline.sweep's work folder, so that a
        Ctrl-C keeps them; else why an interrupted run starts over (shown in --help)."""

    name: str
    figure: str
    summary: str
    compute: Callable
    plot: Callable
    check: Callable
    chosen: str = ""
    records: tuple[str, ...] | None = PAPER_KEYS
    options: Callable | None = None
    not_resumable: str = ""

    @property
    def resumable(self) -> bool:
        return not self.not_resumable

    def _figure_text(self) -> str:
        """Where the recipe stands: the paper's figure(s), or "beyond the paper"."""
        return self.figure if self.figure == BEYOND_THE_PAPER else f"paper {self.figure}"

    def _records_text(self) -> str:
        """The records run without --records: the recipe's own, or (none declared) the pairs
        of a FEMA P695 set (--set, studies.common.options.default_pairs)."""
        if self.records:
            return " ".join(self.records)
        return "the pairs of --set, a few of them with --quick"

    def parser(self) -> argparse.ArgumentParser:
        from engine.parameters import user_text
        from studies.common.program import program

        from .options import add_backend

        epilog = (user_text(f"Values the paper does not state: {self.chosen}")
                  if self.chosen else None)
        p = OneLineParser(
            prog=program(f"studies.{self.name}"),
            description=user_text(f"{self.summary} ({self._figure_text()}). ") + (
                        f"Writes {self.name}.nc, "
                        f"{self.name}.png and {self.name}.pdf into --out. " + (
                            "Ctrl-C keeps the finished simulations: the same command again "
                            "resumes." if self.resumable else "Ctrl-C stops it and keeps "
                            f"nothing: the same command again starts over "
                            f"({user_text(self.not_resumable)}).")),
            epilog=epilog)
        accept_negative_numbers(p)
        if self.records is None:
            unused = "accepted so that one set of options fits every recipe; this recipe " \
                     "runs no records and does not use it"
            p.add_argument("--records-dir", default=None, metavar="DIR", help=unused)
            p.add_argument("--workers", type=int, default=1, help=unused)
            p.add_argument("--scheduler", default=None, metavar="ADDRESS", help=unused)
            p.add_argument("--dt", type=float, default=None, metavar="S", help=unused)
            p.add_argument("--backend", default=None, metavar="NAME", help=unused)
            p.add_argument("--building", action="append", default=[], metavar="FILE|NAME=VALUE",
                           help=unused)
        else:
            p.add_argument("--records", nargs="+", default=list(self.records), metavar="NAME",
                           help="paper keys (kobe, sylmar_converter, olive_view, pacoima), "
                                "library names, RSN<n>:<component> or AT2 paths "
                                f"(default: {self._records_text()})")
            if not self.records:  # the code-based studies: a FEMA P695 set's pairs
                from .options import PAIR_SET

                p.add_argument("--set", choices=FEMA_SETS, default=PAIR_SET,
                               help="the FEMA P695 record set whose pairs run without "
                                    "--records: far-field (22 pairs), near-field-pulse (14), "
                                    f"near-field-no-pulse (14) (default: {PAIR_SET})")
            p.add_argument("--records-dir", default=None, metavar="DIR",
                           help="folder of PEER AT2 files searched first for the paper's "
                                "records (default: $BUMPERS_RECORDS_DIR; else the built-in "
                                "records and the embedded library)")
            p.add_argument("--workers", type=int, default=1,
                           help="1 (default): in this process, the compiled kernel on every "
                                "core through threads; N >= 2: N local dask worker "
                                "processes, one thread each")
            p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                           help="dask.distributed scheduler address to run on instead "
                                "(tcp://HOST:8786, or tls://HOST:8786 with the --tls-* "
                                "options)")
            add_tls_options(p)
            p.add_argument("--dt", type=float, default=None, metavar="S",
                           help="integration step in s (default: the engine's, 0.5 ms)")
            add_backend(p)
            add_text_record_options(p)
            p.add_argument("--building", action="append", default=[],
                           metavar="FILE|NAME=VALUE",
                           help="the building: a TOML or JSON file (see examples/) and/or "
                                "its fields as NAME=VALUE in SI units, e.g. "
                                "zeta_sup=0.03, or masses=500e3,400e3,300e3 with "
                                "story_stiffness=9e8,8e8 (repeatable; default: the paper's "
                                "building)")
        p.add_argument("--out", type=Path, default=Path("results"), metavar="PATH",
                       help=f"where the archive goes: a path ending in .nc is the archive "
                            f"itself (the figures take its stem), one ending in .zarr a Zarr "
                            f"store instead, anything else a folder "
                            f"receiving {self.name}.nc/.png/.pdf (default: results/); "
                            f"finished simulations wait in <archive>.work/ until it is "
                            f"written")
        p.add_argument("--quick", action="store_true",
                       help="a coarse grid, for tests and first looks: written into a quick/ "
                            "folder beside the full run's outputs (never over them) and "
                            "marked as quick in the archive and the figure")
        p.add_argument("--force", action="store_true",
                       help="replace an existing archive of another configuration (without "
                            "it, such an archive is kept and the run refused before any "
                            "compute; the same configuration is replaced silently)")
        p.add_argument("--replot", action="store_true",
                       help=f"redraw the figure from an existing {self.name}.nc, no computing")
        p.add_argument("--quiet", action="store_true", help="no progress bar")
        if self.options is not None:
            self.options(p)
        return p

    def main(self, argv=None) -> int:
        """Run the recipe on argv: its status (2 and one line on bad input; a closed output,
        `| head`, ends it quietly: pipeline.errors.closed_pipe)."""
        from pipeline.errors import closed_pipe

        try:
            return self._main(argv)
        except BrokenPipeError:
            return closed_pipe()

    def _main(self, argv) -> int:
        args = self.parser().parse_args(argv)
        from engine import EngineError
        from pipeline.errors import SweepError, said
        from pipeline.records import RecordError

        try:
            with announce_stand_ins():
                return self._run(args)
        except (EngineError, SweepError, RecordError) as err:
            # Bad input: one line. Anything else is a bug and keeps its traceback.
            print(f"{self.name}: error: {said(err)}", file=sys.stderr)
            return 2
        except KeyboardInterrupt as stop:
            told = interrupted(stop, getattr(args, 'work_dir', None)) if self.resumable else \
                "interrupted: this command keeps no partial results; run it again to start over"
            print(f"{self.name}: {told}",
                  file=sys.stderr)
            return 130

    def _run(self, args) -> int:
        import xarray as xr

        from pipeline.archive import to_netcdf
        from pipeline.building_file import building_from
        from pipeline.cluster import apply_tls_options
        from pipeline.errors import SweepError
        from pipeline.records.lookup import read_text_records
        from pipeline.writing import KEY_ATTRIBUTE, Staged, check_out, guard

        archive, stem = outputs(args.out, self.name, quick=args.quick)
        figures = [Path(f"{stem}.png"), Path(f"{stem}.pdf")]
        if args.replot:
            if not archive.exists():
                raise SweepError(f"--replot needs {archive}, which does not exist")
            for path in figures:
                check_out(path)
            opener = xr.open_zarr if archive.suffix == ".zarr" else xr.open_dataset
            with opener(archive) as opened:
                ds = opened.load()
        else:
            for path in (archive, *figures):
                check_out(path)  # before any compute
            args.building = building_from(args.building)  # a bad building: before compute
            if self.records is not None:
                apply_tls_options(args)
            key = self.configuration_key(args)
            guard(archive, key, args.force)
            if self.records is not None:  # text files read now: a bad one before compute
                args.records = read_text_records(args.records, args.record_units,
                                                 args.record_dt, args.records_dir)
            args.work_dir = archive.with_name(archive.name + ".work")
            ds = self._checked(args)
            ds.attrs[KEY_ATTRIBUTE] = key
        if args.replot:
            for line in _substitutions(ds):
                print(line)
        if "design_basis" in ds.attrs:  # a study on the code's design (studies.common.options)
            print("design basis:", ds.attrs["design_basis"])
        print(ds.attrs["paper_check"])
        fig = self.plot(ds)
        if ds.attrs.get("quick"):
            fig.text(0.5, 1.0, f"QUICK RUN: {QUICK_NOTE}", ha="center", va="bottom",
                     color="firebrick", fontsize=9, fontweight="bold")
        # The archive and its figures are replaced together or not at all.
        with Staged() as stage:
            if not args.replot and archive.suffix == ".zarr":
                ds.to_zarr(stage.folder(archive), mode="w", consolidated=True)
            elif not args.replot:
                to_netcdf(ds, stage.path(archive))
            for path in figures:
                fig.savefig(stage.path(path), format=path.suffix[1:])
            stage.commit()
        import matplotlib.pyplot as plt

        plt.close(fig)
        if args.replot:
            print("redrew", *figures, "from", archive)
        else:
            from pipeline.execute.netcdf_store import WorkFolder

            WorkFolder(args.work_dir).finish()  # another configuration's work is kept
            print("wrote", archive, *figures, *([f"({QUICK_NOTE})"] if args.quick else []))
        return 0

    def dataset(self, argv=None):
        """The recipe's archive as a Dataset, with its verdicts (attributes paper_check and
        paper_verdicts), computed in this process from command-line arguments (argv, as for
        main) and written nowhere: no archive, no figure, no work folder.

            ds = studies.gap_size.recipe.dataset(["--quick"])
        """
        from pipeline.building_file import building_from
        from pipeline.records.lookup import read_text_records

        args = self.parser().parse_args([] if argv is None else list(argv))
        args.building = building_from(args.building)
        if self.records is not None:
            args.records = read_text_records(args.records, args.record_units,
                                             args.record_dt, args.records_dir)
        args.work_dir = None
        return self._checked(args)

    def _checked(self, args):
        """compute, then the verdicts of check, into the Dataset's attributes."""
        ds = self.compute(args)
        ds.attrs.update(recipe=self.name, paper_figure=self.figure, quick=int(args.quick),
                        values_chosen=self.chosen or "none")
        if getattr(args, "set", None) and not args.records:  # the pairs run: a set's
            ds.attrs["record_set"] = f"FEMA P695 {args.set}"
        if args.quick:
            ds.attrs["title"] = f"{ds.attrs.get('title', self.summary)} [{QUICK_NOTE}]"
        verdicts = self.check(ds)
        ds.attrs["paper_check"] = "\n".join(v.text() for v in verdicts)
        ds.attrs["paper_verdicts"] = json.dumps([v.as_dict() for v in verdicts])
        return ds

    def configuration_key(self, args) -> str:
        """What decides this run's numbers: the recipe, every option but those that only say
        how or where to run, the building resolved, the engine's version."""
        from pipeline.provenance import engine_fingerprint
        from pipeline.writing import configuration_key

        chosen = {name: value for name, value in sorted(vars(args).items())
                  if name not in RUN_ONLY}
        return configuration_key(self.name, chosen, engine_fingerprint())


QUICK_NOTE = "coarse grid for tests and first looks, not the paper's resolution"
RUN_ONLY = frozenset({"out", "replot", "quiet", "workers", "scheduler", "batch_size", "force",
                      "work_dir", "tls_ca_file", "tls_cert", "tls_key"})
"""Options that say how or where a recipe runs, not what it computes."""


ARCHIVES = (".nc", ".zarr")
"""What --out may name as the archive itself: a NetCDF file or a Zarr store."""


def outputs(out: Path, name: str, quick: bool = False) -> tuple[Path, Path]:
    """(archive, figure stem) for --out: a path with an archive suffix (ARCHIVES) is the
    archive, anything else a folder receiving NAME.nc. A quick run's go into a quick/ folder
    beside, so that they never replace a full run's."""
    out = Path(out)
    archive = out if out.suffix in ARCHIVES else out / f"{name}.nc"
    if quick:
        archive = archive.parent / "quick" / archive.name
    return archive, archive.with_suffix("")


def interrupted(stop: KeyboardInterrupt, work_dir) -> str:
    """What a Ctrl-C leaves: the simulations kept and where, and how to go on. A stop inside a
    sweep (pipeline.errors.Interrupted) counts its own; anywhere else (resolving records,
    scaling, between sweeps) the work folder's content is counted."""
    from pipeline.errors import Interrupted
    from pipeline.execute.netcdf_store import WorkFolder

    if isinstance(stop, Interrupted):
        return f"{stop}; run the same command again to resume"
    kept = WorkFolder(work_dir).count() if work_dir is not None else 0
    if kept:
        return (f"interrupted: {kept} finished simulations kept in {work_dir}; run the same "
                "command again to resume")
    return ("interrupted before any simulation finished: nothing to keep; run the same "
            "command again to start over")


def add_text_record_options(p: argparse.ArgumentParser) -> None:
    """--record-units and --record-dt: what a one- or two-column text record in --records does
    not say (an AT2 file and a named record state their own)."""
    from pipeline.records.record import UNITS_HELP

    p.add_argument("--record-units", metavar="UNITS",
                   help=f"acceleration units of the text records in --records ({UNITS_HELP})")
    p.add_argument("--record-dt", type=float, metavar="S",
                   help="sampling step of one-column text records, s (two columns: the "
                        "times give it)")


def accept_negative_numbers(parser: argparse.ArgumentParser) -> None:
    """Let option values such as `-1e9` through (argparse reads them as options otherwise),
    so that they reach the range checks and get their messages."""
    import re

    parser._negative_number_matcher = re.compile(
        r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")


def verdict(agrees) -> str:
    """'agrees' / 'differs' for a truth value, 'not tested' for None (nothing to compare)."""
    return "not tested" if agrees is None else ("agrees" if bool(agrees) else "differs")


@dataclass(frozen=True)
class Verdict:
    """One conclusion of the paper against what was computed.

    conclusion: where the paper draws it ("5.1", "4", "3.4", "Eq. 9"); claim: the paper's
    conclusion in one line; finding: what was computed, with its numbers; agrees: True,
    False, or None when the grid holds nothing to compare; numbers: the numbers behind the
    verdict (JSON-able: numbers, strings, lists, dicts), in SI units unless a key says
    otherwise.
    """

    conclusion: str
    claim: str
    finding: str
    agrees: bool | None
    numbers: dict = field(default_factory=dict)

    @property
    def verdict(self) -> str:
        return verdict(self.agrees)

    def text(self) -> str:
        return f"{self.claim} (paper {self.conclusion}); here: {self.finding} -> {self.verdict}."

    def as_dict(self) -> dict:
        from pipeline.provenance import plain

        return {"conclusion": self.conclusion, "claim": self.claim, "finding": self.finding,
                "verdict": self.verdict, "numbers": plain(self.numbers)}


def verdicts(ds) -> list[dict]:
    """The structured verdicts stored in a recipe's archive (a Dataset)."""
    return json.loads(ds.attrs["paper_verdicts"])


def sweep_options(args) -> dict:
    """The pipeline.sweep keywords every record-based recipe passes through: its records and
    run_options."""
    return dict(records=args.records, records_dir=args.records_dir, **run_options(args))


def run_options(args) -> dict:
    """The pipeline.sweep keywords of how and where a recipe runs: its building (resolved by
    Recipe.main from --building), dt, workers, scheduler, quiet and its work folder (set by
    Recipe.main: <archive>.work, shared by all the recipe's sweeps) and the engine's backend."""
    return dict(workers=args.workers, scheduler=args.scheduler, dt=args.dt, quiet=args.quiet,
                building=args.building, work_dir=getattr(args, "work_dir", None),
                backend=args.backend)


NOT_PROVENANCE = frozenset({"title", "configuration_key"})
"""Attributes of a recipe's sweep that are the recipe's own to set in its archive."""


def provenance(swept) -> dict:
    """The provenance of a recipe's sweep (a pipeline.sweep Dataset: versions, commit, dt,
    building, records and their hashes, the sweep's arguments), for an archive the recipe
    builds from it; its title and configuration key are the recipe's own."""
    return {k: v for k, v in swept.attrs.items() if k not in NOT_PROVENANCE}


@contextmanager
def announce_stand_ins():
    """Print a stand-in or plausibility warning (before any compute) or a kept work folder's
    notice (at the end) as one 'warning: ...' line on stderr, when it is raised; other
    warnings keep their usual form."""
    from pipeline.errors import KeptWorkNotice, PlausibilityWarning
    from pipeline.records import StandInWarning

    default = warnings.showwarning

    def show(message, category, filename, lineno, file=None, line=None):
        if issubclass(category, (StandInWarning, PlausibilityWarning, KeptWorkNotice)):
            from engine.parameters import user_text

            print(f"warning: {user_text(str(message))}", file=sys.stderr)
        else:
            default(message, category, filename, lineno, file, line)

    warnings.showwarning = show
    try:
        yield
    finally:
        warnings.showwarning = default


def _substitutions(ds) -> list[str]:
    """Stand-in notes stored by the pipeline, one line each."""
    return [f"note: {value}" for key, value in ds.attrs.items()
            if key.startswith("record_") and key.endswith("_substitution")]
