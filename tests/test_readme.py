"""The documentation holds: README.md and every page of docs/.

Every Python example runs verbatim when saved as a script (an example repeated verbatim runs
once); the front page keeps its two set-up commands; every command and project file the
documentation names exists; every relative link and image points at a file (and a heading)
that exists; every page is linked from the front page.
"""
import functools
import importlib.util
import re
import runpy
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
PAGES = [README, *sorted((ROOT / "docs").glob("*.md"))]


def fenced(page: Path, language: str) -> list[str]:
    """The ```LANGUAGE blocks of a page, in order."""
    return re.findall(rf"```{language}\n(.*?)```", page.read_text(), re.S)


def where(page: Path) -> str:
    return page.relative_to(ROOT).as_posix()


def examples() -> dict[str, str]:
    """Every distinct Python example -> where it first appears (page#index)."""
    found = {}
    for page in PAGES:
        for index, code in enumerate(fenced(page, "python")):
            found.setdefault(code, f"{where(page)}#{index}")
    return found


EXAMPLES = examples()


def test_the_documentation_has_examples():
    assert len(EXAMPLES) >= 5


@pytest.mark.parametrize("code", list(EXAMPLES), ids=list(EXAMPLES.values()))
def test_example_runs_as_a_script(code, tmp_path, monkeypatch, capsys):
    """Saved as a script and run as one (runpy, as `python example.py` runs it: `__name__` is
    "__main__", the working directory the script's own), in this process rather than a new
    one: a new one spent 1.3-2 s of each example importing what this process has imported."""
    script = tmp_path / "example.py"
    script.write_text(code)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(sys, "argv", [str(script)])
    runpy.run_path(str(script), run_name="__main__")
    assert capsys.readouterr().out.strip(), "the example prints its result"


def test_front_page_keeps_its_two_set_up_commands():
    """One command installs and runs the main job, one installs and runs the tests (the
    command .ci/run runs on a fresh machine)."""
    commands = [block.strip() for block in fenced(README, "bash")]
    assert commands == [
        "pip install -e . && python -m studies.gap_size",
        'apt-get install -y libblas3 liblapack3 && pip install -e ".[test]" '
        "&& python -m pytest -q",
    ]
    ci = (ROOT / ".ci" / "run").read_text()
    assert '-e ".[test]"' in ci and "python -m pytest -q" in ci


def shell_lines(page: Path) -> list[str]:
    """The command lines of a page's ```bash blocks, continuations joined, comments dropped."""
    lines = []
    for block in fenced(page, "bash"):
        for line in block.replace("\\\n", " ").splitlines():
            line = line.split(" #")[0].strip()
            if line and not line.startswith("#"):
                lines.append(line)
    return lines


def named_commands(page: Path) -> list[str]:
    """Every command and file a page names in its bash blocks and its `code`: python -m
    MODULE, python FILE.py, bumpers NAME, --building FILE (from the project's root), and paths
    of the project's files such as `engine/units.py` (any folder may hold them: a path may be
    relative to its package). Placeholders in capitals, outputs and made-up paths left out."""
    text = page.read_text()
    code = shell_lines(page) + re.findall(r"`([^`\n]+)`", text)
    found = []
    for line in code:
        found += [f"module {m}" for m in re.findall(r"python -m ([\w.]+)", line)]
        found += [f"file {f}" for f in re.findall(r"python ([\w/.-]+\.py)\b", line)]
        found += [f"file {f}" for f in re.findall(r"--building ([\w/.-]+\.(?:toml|json))", line)]
        found += [f"bumpers {n}" for n in re.findall(r"^bumpers ([a-z_]+)", line)]
        found += [f"path {p}" for p in re.findall(
            r"(?<![\w/.])((?:[\w.-]+/)+[\w.-]+\.(?:py|toml|json|nc|md))\b", line)
            if not p.startswith("results/") and "path/to/" not in p]
    return [name for name in found if not re.search(r"\b[A-Z]{3,}\b", name)]


@functools.cache
def project_files() -> tuple[str, ...]:
    """The project's files, as paths from its root (hidden folders and outputs left out)."""
    skip = {"results", "__pycache__"}
    return tuple(p.relative_to(ROOT).as_posix() for p in ROOT.rglob("*")
                 if p.is_file() and not any(part.startswith(".") or part in skip
                                            or part.endswith(".egg-info")
                                            for part in p.relative_to(ROOT).parts))


@pytest.mark.parametrize("page", PAGES, ids=where)
def test_every_command_and_file_named_exists(page):
    from studies.cli import commands

    known = {command.name for command in commands()}
    for name in named_commands(page):
        kind, _, what = name.partition(" ")
        if kind == "module":
            assert importlib.util.find_spec(what) is not None, f"{where(page)}: {name}"
        elif kind == "file":
            assert (ROOT / what).is_file(), f"{where(page)}: {name}"
        elif kind == "path":
            assert any(f == what or f.endswith(f"/{what}") for f in project_files()), \
                f"{where(page)}: {name}"
        else:
            assert what in known, f"{where(page)}: {name}"


def anchors(page: Path) -> set[str]:
    """The anchors GitHub gives a page's headings: lower case, punctuation dropped, spaces
    to hyphens."""
    headings = re.findall(r"^#+ (.+)$", page.read_text(), re.M)
    return {re.sub(r"[^\w\- ]", "", h.strip().lower()).replace(" ", "-") for h in headings}


@pytest.mark.parametrize("page", PAGES, ids=where)
def test_every_relative_link_and_image_exists(page):
    text = re.sub(r"```.*?```", "", page.read_text(), flags=re.S)
    for target in re.findall(r"\]\(([^)\s]+)\)", text):
        if re.match(r"[a-z]+:", target):
            continue  # an absolute URL
        path, _, anchor = target.partition("#")
        linked = (page.parent / path).resolve() if path else page
        assert linked.exists(), f"{where(page)}: {target}"
        if anchor:
            assert anchor in anchors(linked), f"{where(page)}: {target}: no such heading"


def test_every_page_is_linked_from_the_front_page():
    text = README.read_text()
    for page in PAGES[1:]:
        assert f"]({where(page)})" in text, f"README.md does not link {where(page)}"


def sweep_commands() -> list[tuple[str, str]]:
    """(page, command) of every sweep the pages give to run (`python -m studies.sweep ...` or
    `bumpers sweep ...`, in a bash block or in `code`, a span broken over lines too), the
    command named alone and help requests left out."""
    found = []
    for page in PAGES:
        prose = re.sub(r"```.*?```", "", page.read_text(), flags=re.S)  # the blocks: above
        spans = [" ".join(span.split()) for span in re.findall(r"`([^`]+)`", prose)]
        for line in shell_lines(page) + spans:
            for command in re.findall(r"((?:python -m studies\.sweep|bumpers sweep)\b[^;&|]*)",
                                      line):
                words = command.split()
                arguments = words[2 if words[0] == "bumpers" else 3:]  # the command's own
                if arguments and not {"--help", "-h"} & set(arguments):
                    found.append((where(page), " ".join(words)))
    return found


def test_every_documented_sweep_writes_an_output_of_its_own():
    """Issue 40: three documented sweeps wrote the same default output, so that run in the
    order the docs give, the second was refused (an archive of another sweep). Each names its
    --out, and two different sweeps never the same one."""
    commands = sweep_commands()
    assert len(commands) >= 3
    outputs = {}
    for page, command in commands:
        out = re.search(r"--out (\S+)", command)
        assert out, f"{page}: `{command}` names no --out"
        outputs.setdefault(out.group(1), set()).add(command)
    shared = {out: sorted(c) for out, c in outputs.items() if len(c) > 1}
    assert not shared, f"sweeps writing the same output: {shared}"
