"""docs/variables.md, the page of a sweep's archive variables, written from their declarations.

    python tools/variables_page.py            print the page
    python tools/variables_page.py --write    write docs/variables.md

What a sweep's archive (pipeline.sweep, python -m studies.sweep) and a histories archive
(pipeline.histories, --history) hold, each variable with its unit and long name as the archive
writes them: the engine's results (engine.results: PEAKS, RESIDUALS, COLLAPSE, PLAN_PEAKS,
TORSION_PEAKS and the histories), the blocks' prefixes, the derived variables and the validity flags
(pipeline.assess.sweep_variables, pipeline.assess.validity), and the swept parameters'
coordinates (the laws' declarations). tests/test_variables_page.py checks that the page is
this text, so that it cannot drift from the code.

    python tools/variables_page.py --write --studies   also run every study

The studies' own archives add variables of their own, labelled where each study computes them
(pipeline.archive.labelled_dataset refuses a variable without units and long name): with
--studies every recipe of studies/ runs in its --quick form (a few minutes) and the page's last
part lists, per archive, each variable the sweep's part does not, with the units, dims and long
name that archive gives it. Without --studies that part is kept as the page has it; the studies'
tests (tests/helpers.assert_on_variables_page) check each archive they build against it.
"""
from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "variables.md"
STUDIES_MARK = "## The studies' archives"
"""The heading of the page's last part: the studies' own variables, harvested (--studies)."""
SWEEP_PREFIXES = ("baseline_", "unconstrained_")


def _table(rows, dims: str = "dims beyond record and the swept parameters") -> list[str]:
    return [f"| name | units | {dims} | meaning |",
            "|---|---|---|---|", *(f"| `{n}` | {u} | {d} | {m} |" for n, u, d, m in rows)]


def _quantities(quantities) -> list[tuple[str, str, str, str]]:
    rows = []
    for q in quantities:
        dims = [q.along] if q.along else []
        if q.direction:
            dims.append("direction")
        meaning = q.long_name + (f" (flags: {', '.join(q.flags)})" if q.flags else "")
        rows.append((q.name, f"`{q.units}`", ", ".join(dims) or "-", meaning))
    return rows


def page() -> str:
    """The page's text."""
    sys.path.insert(0, str(ROOT))
    from engine.results import (
        COLLAPSE,
        HISTORIES,
        PEAKS,
        PLAN_HISTORIES,
        PLAN_PEAKS,
        RESIDUALS,
        TORSION_HISTORIES,
        TORSION_PEAKS,
    )
    from pipeline.archive import parameter_meta
    from pipeline.assess.sweep_variables import AMPLIFICATION, STORY_DUCTILITY
    from pipeline.assess.validity import FLAGS
    from pipeline.execute.zarr_store import RESUME_RECORD
    from pipeline.members import EXCITATION_PARAMS, ISOLATOR_PARAMS, PARAMS

    lines = [
        "# Archive variables",
        "",
        "<!-- written by `python tools/variables_page.py --write` from the declarations; a "
        "test keeps it current -->",
        "",
        "What a sweep's archive (`pipeline.sweep`, `python -m studies.sweep`) and a histories "
        "archive (`pipeline.histories`, `--history`) hold, each variable with the unit and long "
        "name the archive gives it ([archives](archives.md) says how they are laid out). Every "
        "peak is over the whole run (up to its collapse, where it collapsed). The studies' own "
        "archives add variables of their own: [the last part](#the-studies-archives) lists "
        "them, and each study's section of [beyond the paper](studies.md) reads them.",
        "",
        "## Peaks (every sweep)",
        "",
        *_table(_quantities(PEAKS)),
        "",
        "What stays at the end of the run (resultants in plan, at the plan's centre in a "
        "building that twists):",
        "",
        *_table(_quantities(RESIDUALS)),
        "",
        "With a collapse criterion (a building's `collapse_drift_ratio`, an isolator's "
        "capacity):",
        "",
        *_table(_quantities(COLLAPSE)),
        "",
        "## In plan and twisting (`--moat`)",
        "",
        "The peaks above are then resultants (vector magnitudes); besides them:",
        "",
        *_table(_quantities(PLAN_PEAKS)),
        "",
        "A building that twists (a `torsion` component) adds:",
        "",
        *_table(_quantities(TORSION_PEAKS)),
        "",
        "## Blocks",
        "",
        "`--baseline` adds `baseline_<peak>` (the bare wall at each gap: the linear law at its "
        "defaults) and `--unconstrained` adds `unconstrained_<peak>` (no wall), each peak above "
        "under that prefix, without the wall's parameters among its dims.",
        "",
        "## Derived",
        "",
        *_table([*((name, "`1`", "as the peak", text)
                   for name, (_, text) in AMPLIFICATION.items()),
                 *_quantities([STORY_DUCTILITY]),
                 *((name, "`1`", "-", f"1 where {text}") for name, text in FLAGS.items())]),
        "",
        "The amplifications exist with `--baseline`, the ductility where the stories yield; the "
        "flags are computed at their default limits (`validity_limits` says which).",
        "",
        "## Coordinates: the swept parameters",
        "",
        "| name | units | meaning |",
        "|---|---|---|",
    ]
    laws = ("bumper", "linear", "jankowski", "hertzdamp")
    for name in PARAMS:
        units, long_name = parameter_meta(laws, name)
        lines.append(f"| `{name}` | `{units}` | {long_name} |")
    lines += ["", f"The isolator's ({', '.join(f'`{n}`' for n in ISOLATOR_PARAMS)}) and the "
              f"excitation's ({', '.join(f'`{n}`' for n in EXCITATION_PARAMS)}) are "
              "coordinates too when swept, with the units and long names their laws declare.",
              "", "## Histories (`pipeline.histories`, `--history`)", "",
              "Against `time` (s), per `configuration`, besides the peaks above:", "",
              *_table(_quantities(HISTORIES)), "", "In plan (`engine.simulate`'s history):", "",
              *_table(_quantities(PLAN_HISTORIES)), "", "A building that twists:", "",
              *_table(_quantities(TORSION_HISTORIES)), "",
              "## Zarr stores (`out` ending in `.zarr`)", "",
              "Besides the variables above, the resume record, one element per batch:", "",
              *_table([(name, f"`{units}`", "batch", text)
                       for name, (_, units, text) in RESUME_RECORD.items()], "dims"), ""]
    return "\n".join(lines)


def studies_part(text: str) -> str:
    """The page's last part (from STUDIES_MARK on) in `text`; "" when it has none."""
    at = text.find("\n" + STUDIES_MARK + "\n")
    return "" if at < 0 else text[at + 1:]


def listed_by_archive(text: str) -> dict[str, dict[str, str]]:
    """archive file name -> {variable: units} of the studies' part of a page's `text`."""
    import re

    listed, current = {}, None
    for line in studies_part(text).splitlines():
        heading = re.match(r"^### `([^`]+)`", line)
        if heading:
            current = listed.setdefault(heading.group(1), {})
        row = re.match(r"^\| `(\w+)` \| `?([^`|]*)`? \|", line)
        if row and current is not None:
            current[row.group(1)] = row.group(2).strip()
    return listed


def sweep_names(text: str) -> set[str]:
    """The variables and coordinates the sweep's part of a page's `text` lists."""
    import re

    return set(re.findall(r"^\| `(\w+)` \|", text[:len(text) - len(studies_part(text))],
                          re.M))


def own_variables(ds, known: set[str]) -> list[tuple[str, str, str, str]]:
    """(name, units, dims, long name) of `ds`'s variables and labelled coordinates that the
    sweep's part (`known`) does not list, a block's prefix aside."""
    rows = []
    for name, var in {**ds.coords, **ds.data_vars}.items():
        own = str(name)
        for prefix in SWEEP_PREFIXES:
            own = own.removeprefix(prefix)
        if own in known or "long_name" not in var.attrs:
            continue
        units = var.attrs.get("units")
        rows.append((str(name), f"`{units}`" if units is not None else "text",
                     ", ".join(map(str, var.dims)) or "-",
                     " ".join(str(var.attrs["long_name"]).split()).replace("|", "\\|")))
    return sorted(rows)


def recipes() -> list[str]:
    """The studies run by --studies: every recipe of studies/ (the loss study after the
    collapse study, whose archive it reads)."""
    sys.path.insert(0, str(ROOT))
    from studies.cli import recipe_names

    return sorted(recipe_names(), key=lambda n: n == "loss")


def harvest(known: set[str]) -> str:
    """Run every recipe in its --quick form in a temporary folder and list each archive's own
    variables (the page's last part)."""
    import xarray as xr

    lines = [STUDIES_MARK, "",
             "<!-- written by `python tools/variables_page.py --write --studies`, from every "
             "study's --quick archive; the studies' tests check their archives against it -->",
             "", "Each study's archive holds, besides the sweep's variables above (where it "
             "runs a sweep), the variables below: their units, dims and long names as the "
             "archive gives them (those of a --quick run: a full run's are the same).", ""]
    with tempfile.TemporaryDirectory() as folder:
        out = Path(folder)
        for name in recipes():
            extra = ["--collapse", str(out / "collapse" / "quick" / "collapse.nc")] \
                if name == "loss" else []
            print(f"running studies.{name} --quick", file=sys.stderr, flush=True)
            subprocess.run([sys.executable, "-m", f"studies.{name}", "--quick", "--quiet",
                            "--out", str(out / name), *extra], cwd=ROOT, check=True,
                           stdout=subprocess.DEVNULL)
            for path in sorted((out / name).rglob("*.nc")):
                with xr.open_dataset(path) as ds:
                    rows = own_variables(ds, known)
                lines += [f"### `{path.name}` (`python -m studies.{name}`)", ""]
                lines += [*_table(rows, "dims"), ""] if rows \
                    else ["Only the sweep's variables.", ""]
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", action="store_true", help="write docs/variables.md")
    parser.add_argument("--studies", action="store_true",
                        help="run every study in its --quick form (minutes) and list their "
                        "archives' own variables; without it the page keeps that part as it is")
    args = parser.parse_args(argv)
    text = page()
    if args.studies:
        text += "\n" + harvest(sweep_names(text))
    elif PAGE.exists() and studies_part(PAGE.read_text()):
        text += "\n" + studies_part(PAGE.read_text())
    if args.write:
        PAGE.write_text(text)
        print(f"wrote {PAGE.relative_to(ROOT)}")
    else:
        print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
