"""The `bumpers` console command (studies/cli.py): it lists every command found on disk, runs
one with its arguments and exit status, and refuses an unknown one in one line."""
import importlib
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from studies import cli

ROOT = Path(__file__).resolve().parents[2]
RECIPES = sorted([p.stem for p in (ROOT / "studies").glob("*.py")
                  if not p.stem.startswith("_") and p.stem not in ("cli", "sweep")]
                 + [p.parent.name for p in (ROOT / "studies").glob("*/__main__.py")])
"""The recipes on disk, modules and packages run with `python -m` (a package has a
__main__.py), found here independently of cli's pkgutil discovery."""


def listed(text: str) -> list[str]:
    """The command names of a listing: the first word of each entry line."""
    lines = text[text.index("commands:"):].splitlines()[1:]
    return [line.split()[0] for line in lines if line.startswith("  ") and line[2] != " "]


def installed_bumpers() -> str:
    """The console script pip installed beside this Python (else the one on PATH)."""
    found = shutil.which("bumpers", path=str(Path(sys.executable).parent)) \
        or shutil.which("bumpers")
    assert found, "no `bumpers` script: run pip install -e . again"
    return found


def test_recipes_are_found_on_disk():
    assert len(RECIPES) >= 11 and "gap_size" in RECIPES
    assert cli.recipe_names() == RECIPES


@pytest.mark.parametrize("argv", [["--help"], ["-h"], []])
def test_help_lists_every_recipe_then_sweep_and_records(argv, capsys):
    assert cli.main(argv) == 0
    names = listed(capsys.readouterr().out)
    assert sorted(names[:-4]) == RECIPES
    assert names[-4:] == ["sweep", "export", "plot", "records"]
    assert names[0] == "impact_validation"  # the paper's order: Fig. 6 first


def test_listing_reads_what_the_recipes_declare():
    """The summaries read from the sources are those of the imported recipes."""
    for command in cli.commands()[:-4]:
        recipe = importlib.import_module(command.module).recipe
        assert (command.name, command.figure, command.summary) == \
               (recipe.name, recipe.figure, recipe.summary)


def test_a_recipe_that_is_not_literal_is_imported():
    assert cli.literal_recipe("recipe = Recipe(figure='Fig. 1', summary=f'{X} cm')") is None
    assert cli.literal_recipe("recipe = Recipe(figure='Fig. 1', summary='a' 'b')") == \
           {"figure": "Fig. 1", "summary": "ab"}


def test_listing_imports_no_recipe():
    """`bumpers --help` stays fast: no recipe, matplotlib, numba or xarray imported."""
    code = ("import sys; from studies.cli import main; main(['--help']); "
            "print(sorted(m for m in sys.modules if m.split('.')[0] in "
            "('matplotlib', 'numba', 'xarray', 'engine') or m.startswith('studies.g')))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=60, check=True)
    assert done.stdout.splitlines()[-1] == "[]"


def test_unknown_command_is_one_line_naming_the_commands(capsys):
    assert cli.main(["gap_sizes", "--quick"]) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    assert len(captured.err.strip().splitlines()) == 1
    assert "'gap_sizes'" in captured.err
    assert all(name in captured.err for name in [*RECIPES, "sweep", "records"])


@pytest.mark.parametrize("name, module", [("gap_size", "studies.gap_size"),
                                          ("sweep", "studies.sweep"),
                                          ("records", "pipeline.records.cli")])
def test_arguments_and_status_pass_through(name, module, monkeypatch):
    seen = []

    def fake_main(argv=None):
        seen.append(argv)
        return 7

    monkeypatch.setattr(importlib.import_module(module), "main", fake_main)
    assert cli.main([name, "--quick", "--out", "/tmp/x"]) == 7
    assert seen == [["--quick", "--out", "/tmp/x"]]


def test_command_help_is_the_commands_own(capsys):
    assert cli.main(["gap_size", "--help"]) == 0
    assert "usage: bumpers gap_size" in capsys.readouterr().out


def test_an_option_is_taken_by_its_whole_name_only(capsys):
    """`--records kobe` in a recipe without --records was taken for --records-dir (argparse's
    prefix matching) and the recipe ran; now refused before anything runs."""
    assert cli.main(["impact_validation", "--records", "kobe"]) == 2
    assert "unrecognized arguments: --records kobe" in capsys.readouterr().err
    assert cli.main(["records", "--records", "x"]) == 2


def test_usage_error_of_a_command_is_status_2(capsys):
    assert cli.main(["records", "--no-such-option"]) == 2
    assert "unrecognized arguments" in capsys.readouterr().err


def test_the_installed_console_script_runs_a_command():
    script = installed_bumpers()
    done = subprocess.run([script, "records", "--help"], capture_output=True, text=True,
                          timeout=60)
    assert done.returncode == 0, done.stderr
    assert "usage: bumpers records" in done.stdout
    unknown = subprocess.run([script, "nope"], capture_output=True, text=True, timeout=60)
    assert unknown.returncode == 2
    assert unknown.stderr.count("\n") == 1 and unknown.stdout == ""


@pytest.mark.parametrize("argv", [[], ["--help"], ["records"], ["records", "--paper-only"]])
def test_a_reader_that_goes_ends_the_command_quietly(argv):
    """Issue 40: `bumpers | head`, `bumpers --help | head` and `bumpers records | head` ended
    in a BrokenPipeError traceback. With its output closed before it writes (the reader gone),
    a command now ends without a word on stderr, with a shell's status for it (141)."""
    from pipeline.errors import CLOSED_PIPE_STATUS

    process = subprocess.Popen([sys.executable, "-m", "studies.cli", *argv],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               cwd=Path(cli.__file__).resolve().parents[1])
    process.stdout.close()  # before the command starts writing: it imports first
    err = process.stderr.read().decode()
    assert process.wait(timeout=120) == CLOSED_PIPE_STATUS and err == ""
