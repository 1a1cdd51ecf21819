"""The map of the code in docs/model.md, written from the packages' own docstrings.

    python tools/code_map.py            print the map
    python tools/code_map.py --write    put it into docs/model.md, between its markers

One entry per package (a folder with __init__.py) of engine/, pipeline/ and studies/: the
first paragraph of the package's docstring, then each of its modules with the first sentence of
the module's docstring. tests/test_layout.py checks that docs/model.md holds exactly this map,
so that it cannot drift from the code.
"""
from __future__ import annotations

import argparse
import ast
import re
import sys
from pathlib import Path

PACKAGES = ("engine", "pipeline", "studies")
BEGIN = "<!-- the map of the code: written by `python tools/code_map.py --write` -->"
END = "<!-- end of the map of the code -->"


def docstring(path: Path) -> str:
    return ast.get_docstring(ast.parse(path.read_text())) or ""


def first_paragraph(text: str) -> str:
    return " ".join(text.split("\n\n")[0].split())


ABBREVIATIONS = ("Eq", "Eqs", "e.g", "i.e", "Fig", "Figs", "al", "vs", "cf", "No", "etc")


def first_sentence(text: str) -> str:
    """The first sentence of a docstring's first paragraph (a period after an abbreviation
    such as "Eq." does not end it)."""
    paragraph = first_paragraph(text)
    for match in re.finditer(r"\.(\s|$)", paragraph):
        words = paragraph[:match.start()].split()
        if words and words[-1].lstrip("(") not in ABBREVIATIONS:
            return paragraph[:match.start()]
    return paragraph


def table(root: Path) -> str:
    """The map as markdown: one bullet per package, its modules after it."""
    lines = [BEGIN]
    for package in PACKAGES:
        for init in sorted((root / package).rglob("__init__.py")):
            folder = init.parent
            relative = folder.relative_to(root).as_posix()
            lines.append(f"- **`{relative}/`**: {first_paragraph(docstring(init))}")
            for module in sorted(folder.glob("*.py")):
                if module.name == "__init__.py":
                    continue
                lines.append(f"  - `{module.name}`: {first_sentence(docstring(module))}")
    lines.append(END)
    return "\n".join(lines)


def write(root: Path) -> bool:
    """Replace the map in docs/model.md; whether it changed."""
    doc = root / "docs" / "model.md"
    text = doc.read_text()
    start, stop = text.find(BEGIN), text.find(END)
    if start < 0 or stop < 0:
        raise SystemExit(f"{doc}: the markers of the map are missing ({BEGIN} ... {END})")
    new = text[:start] + table(root) + text[stop + len(END):]
    doc.write_text(new)
    return new != text


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--write", action="store_true",
                        help="put the map into docs/model.md instead of printing it")
    args = parser.parse_args(argv)
    root = Path(__file__).resolve().parents[1]
    if args.write:
        print("docs/model.md:", "map rewritten" if write(root) else "map unchanged")
    else:
        print(table(root))
    return 0


if __name__ == "__main__":
    sys.exit(main())
