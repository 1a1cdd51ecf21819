"""docs/variables.md, the page of a sweep's archive variables, written from their declarations.

    python tools/variables_page.py            print the page
    python tools/variables_page.py --write    write docs/variables.md

What a sweep's archive (pipeline.sweep, python -m studies.sweep) and a histories archive
(pipeline.histories, --history) hold, each variable with its unit and long name as the archive
writes them: the engine's results (engine.results: PEAKS, RESIDUALS, COLLAPSE, PLAN_PEAKS,
TORSION_PEAKS and the histories), the blocks' prefixes, the derived variables and the validity flags
(pipeline.assess.sweep_variables, pipeline.assess.validity), and the swept parameters'
coordinates (the laws' declarations). tests/test_variables_page.py checks that the page is
this text, so that it cannot drift from the code. The studies' own archives add variables of
their own, which each study's section of docs/studies.md describes.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "variables.md"


def _table(rows) -> list[str]:
    return ["| name | units | dims beyond record and the swept parameters | meaning |",
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
        "archives add variables of their own, described in their sections of "
        "[beyond the paper](studies.md).",
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
              *_table(_quantities(TORSION_HISTORIES)), ""]
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", action="store_true", help="write docs/variables.md")
    args = parser.parse_args(argv)
    text = page()
    if args.write:
        PAGE.write_text(text)
        print(f"wrote {PAGE.relative_to(ROOT)}")
    else:
        print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
