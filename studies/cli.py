"""The `bumpers` command: one entry point for every command of the project.

    bumpers                   the commands, each with its one-line summary (also --help)
    bumpers NAME [ARGS...]    run command NAME with ARGS: its own options, --help, exit status

The commands are every recipe of studies/ (a module whose name does not start with "_",
defining `recipe` and `main`; found on disk, so a new recipe is a new command with nothing to
register), then `sweep` (studies.sweep), `export` and `plot` (studies.archive_tools: on a
sweep's archive) and `records` (pipeline.records). `bumpers NAME ARGS` is `python -m
studies.NAME ARGS` (`python -m studies.archive_tools.NAME ARGS` for export and plot, `python -m
pipeline.records ARGS` for records), which keeps working as it is.

The listing reads each recipe's figure and summary from the literal arguments of its
`Recipe(...)` in the module's source rather than importing it: importing every recipe would
load matplotlib and the engine for a help text. A recipe whose `Recipe(...)` is not written
with literal strings is imported instead, so the listing is right either way.
"""
from __future__ import annotations

import ast
import importlib
import importlib.util
import os
import pkgutil
import re
import shutil
import sys
import textwrap
from dataclasses import dataclass

from .common.program import RUNNING, program  # noqa: F401 - program: the name in use

PACKAGE = "studies"
PROGRAM_ENV = "BUMPERS_PROGRAM"
"""The environment variable that names the command `bumpers` runs, for the commands of
pipeline/ (which import nothing of studies/)."""
NOT_RECIPES = frozenset({"cli", "sweep", "common", "archive_tools"})
"""Modules of studies/ that are not recipes (cli: this one; sweep: a command of its own;
common: what the recipes share; archive_tools: the export and plot commands)."""


@dataclass(frozen=True)
class Command:
    """A command of `bumpers`: its name, the module whose `main(argv)` runs it, and the
    figure of the paper it draws ("" for none) with its one-line summary."""

    name: str
    module: str
    figure: str
    summary: str


OTHERS = (
    Command("sweep", "studies.sweep", "",
            "Any parameter grid: every combination of gaps, bumpers, walls and isolator "
            "values under the given records, peaks into a NetCDF or Zarr archive"),
    Command("export", "studies.archive_tools.export", "",
            "A sweep archive's peaks as a CSV table (one row per run, columns with units) or "
            "as a pelicun demand sample (PFA in g, PID drift ratios)"),
    Command("plot", "studies.archive_tools.plot", "",
            "A peak of a sweep archive against one of its swept dimensions, one line per "
            "value of the others (or their median and 16-84% band)"),
    Command("records", "pipeline.records.cli", "",
            "Where the paper's records are found (records folder, built-in data, library or "
            "stand-in), then the embedded ground-motion library"),
)
"""The commands that are not recipes, listed after them."""


def recipe_names() -> list[str]:
    """The recipe modules of studies/, as found on disk."""
    package = importlib.import_module(PACKAGE)  # its __init__ is a docstring: light
    return sorted(m.name for m in pkgutil.iter_modules(package.__path__)
                  if not m.name.startswith("_") and m.name not in NOT_RECIPES)


def literal_recipe(source: str) -> dict[str, str] | None:
    """figure and summary of the module-level `recipe = Recipe(...)` in `source`, when both
    are literal strings; None otherwise."""
    for node in ast.parse(source).body:
        if not (isinstance(node, ast.Assign) and isinstance(node.value, ast.Call)
                and [getattr(t, "id", None) for t in node.targets] == ["recipe"]
                and getattr(node.value.func, "id", None) == "Recipe"):
            continue
        found = {k.arg: k.value.value for k in node.value.keywords
                 if isinstance(k.value, ast.Constant) and isinstance(k.value.value, str)}
        wanted = ("figure", "summary")
        return {k: found[k] for k in wanted} if all(k in found for k in wanted) else None
    return None


def recipe_command(name: str) -> Command:
    """The command of recipe module studies.NAME, read from its source (or, failing that,
    from the imported module's `recipe`)."""
    module = f"{PACKAGE}.{name}"
    spec = importlib.util.find_spec(module)
    with open(spec.origin, encoding="utf-8") as source:
        fields = literal_recipe(source.read())
    if fields is None:
        recipe = importlib.import_module(module).recipe
        fields = {"figure": recipe.figure, "summary": recipe.summary}
    # The command is the module's name: that is what `python -m studies.NAME` runs.
    return Command(name, module, fields["figure"], fields["summary"])


def paper_order(command: Command) -> tuple:
    """Sort key: the paper's figures in the paper's order (by their first number), then
    the studies beyond the paper by name."""
    number = re.search(r"\d+", command.figure)
    return (0, int(number.group()), command.name) if number else (1, 0, command.name)


def commands() -> list[Command]:
    """Every command: the recipes in the paper's order, then sweep, export, plot and
    records."""
    return sorted(map(recipe_command, recipe_names()), key=paper_order) + list(OTHERS)


def listing(found: list[Command]) -> str:
    """The help text: usage, then each command with its summary and the paper's figure."""
    width = min(shutil.get_terminal_size((100, 24)).columns, 100)
    column = max(len(c.name) for c in found) + 4
    intro = ("The commands of bumpers, the paper's figures in the paper's order. "
             "`bumpers COMMAND ARGS` runs `python -m studies.COMMAND ARGS` (records: "
             "`python -m pipeline.records ARGS`); `bumpers COMMAND --help` shows its options.")
    lines = ["usage: bumpers COMMAND [ARGS...]", "",
             *textwrap.wrap(intro, width, break_on_hyphens=False), "", "commands:"]
    for command in found:
        text = f"{command.summary} ({command.figure})" if command.figure else command.summary
        lines += textwrap.wrap(text, width, initial_indent=f"  {command.name:<{column - 2}}",
                               subsequent_indent=" " * column, break_on_hyphens=False)
    return "\n".join(lines)


def run(module: str, argv: list[str], name: str | None = None) -> int:
    """Run `module.main(argv)` and return its exit status, as `python -m` would end; name: the
    command's name under `bumpers` (its help and errors then say `bumpers NAME`)."""
    if name:
        RUNNING[module] = name
        # a command outside studies/ (pipeline.records) cannot read RUNNING: it reads this
        os.environ[PROGRAM_ENV] = f"bumpers {name}"
    try:
        status = importlib.import_module(module).main(argv)
    except SystemExit as stop:  # argparse's --help and usage errors end this way
        status = stop.code
    finally:
        RUNNING.pop(module, None)
        os.environ.pop(PROGRAM_ENV, None)
    if status is None or isinstance(status, int):
        return status or 0
    print(status, file=sys.stderr)  # SystemExit("message"): Python prints it, status 1
    return 1


def version() -> str:
    """The installed version of bumpers."""
    from importlib.metadata import PackageNotFoundError
    from importlib.metadata import version as installed

    try:
        return installed("bumpers")
    except PackageNotFoundError:
        return "unknown (not installed)"


def main(argv: list[str] | None = None) -> int:
    """`bumpers [NAME [ARGS...]]`: list the commands, or run one and return its status (a
    closed output, `bumpers | head`, ends it quietly: pipeline.errors.closed_pipe)."""
    from pipeline.errors import closed_pipe

    try:
        return _main(sys.argv[1:] if argv is None else list(argv))
    except BrokenPipeError:
        return closed_pipe()


def _main(argv: list[str]) -> int:
    if not argv or argv[0] in ("-h", "--help"):
        print(listing(commands()))
        return 0
    if argv[0] == "--version":
        print(f"bumpers {version()}")
        return 0
    found = {c.name: c for c in commands()}
    if argv[0] not in found:
        kind = "option" if argv[0].startswith("-") else "command"
        print(f"bumpers: unknown {kind} {argv[0]!r}; the commands are {', '.join(found)} "
              "(bumpers --help describes them)", file=sys.stderr)
        return 2
    return run(found[argv[0]].module, argv[1:], argv[0])


if __name__ == "__main__":
    # `python -m studies.cli` runs this file as __main__, a module apart from studies.cli,
    # which the commands read `program` from: run that one.
    raise SystemExit(importlib.import_module("studies.cli").main())
