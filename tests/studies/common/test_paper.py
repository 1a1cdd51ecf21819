"""studies/ layout: the paper's fixed choices (studies.common.paper) agree with the bumper law's
declared defaults where both hold one, reproduce the paper's own numbers, and no recipe
imports another recipe."""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

from engine.impact import LAWS
from engine.units import KN_PER_MM
from pipeline.grid import BASELINE
from studies.common import paper

STUDIES = Path(__file__).resolve().parents[3] / "studies"
NOT_RECIPES = {"__init__", "cli", "common", "__pycache__"}


def test_practical_bumper_is_the_laws_default():
    """The law took its defaults from the paper's practical bumper (section 4): the two must
    not drift apart."""
    declared = LAWS["bumper"].PARAMETERS
    assert paper.THICKNESS == declared.thickness.default == 0.05
    assert paper.N_BUMPERS == declared.n_bumpers.default == 4
    assert paper.STRAIN == declared.strain.default == 0.8
    assert paper.WALL_K == declared.k_w.default == 1500 * KN_PER_MM
    assert paper.TEST_COR == declared.cor.default == 0.45


def test_paper_numbers():
    # the gap rule gives the paper's gaps from its unconstrained peaks, to the cm
    for record, gap in paper.PRACTICAL_GAPS.items():
        assert round(paper.GAP_FRACTION * paper.PRACTICAL_UNCONSTRAINED[record], 2) == gap
    assert [k / KN_PER_MM for k in paper.FIG21_WALL_KS] == [2500, 1500, 500]
    assert paper.FIG21_WALL_KS[0] == BASELINE["wall_k"]  # the stiffest is the bare wall's
    assert paper.WALL_K in paper.FIG21_WALL_KS and paper.N_BUMPERS in paper.FIG19_COUNTS
    assert paper.GAP_RANGE_CM == (15, 45)
    assert paper.TEST_PAD_AREA == pytest.approx(0.040 * 0.040, rel=1e-15)


def _recipe_files(name: str) -> list[Path]:
    """The files of recipe `name`: its module, or every module of its package."""
    package = STUDIES / name
    return sorted(package.glob("*.py")) if package.is_dir() else [STUDIES / f"{name}.py"]


def _studies_imports(path: Path) -> set[str]:
    """The first part after `studies.` of every module of studies/ that `path` imports
    (relative or absolute): "common", a recipe's name, or the module's own package."""
    package = path.parent.relative_to(STUDIES.parent).parts  # ("studies",) or (.., "suite")
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = list(package[:len(package) - node.level + 1])
                target = base + (node.module.split(".") if node.module else [])
                names = [a.name for a in node.names]
            elif node.module and node.module.split(".")[0] == "studies":
                target, names = node.module.split("."), [a.name for a in node.names]
            else:
                continue
            found |= {target[1]} if len(target) > 1 else set(names)
        elif isinstance(node, ast.Import):
            found |= {a.name.split(".")[1] for a in node.names
                      if a.name.startswith("studies.")}
    return found


RECIPES = sorted({p.stem if p.is_file() else p.name for p in STUDIES.iterdir()
                  if (p.suffix == ".py" or (p / "__init__.py").is_file())} - NOT_RECIPES)


@pytest.mark.parametrize("name", RECIPES)
def test_no_recipe_imports_another(name):
    """Recipes (and the general sweep) import only what the recipes share (studies.common)
    and, in a recipe's package, its own modules."""
    for path in _recipe_files(name):
        assert _studies_imports(path) <= {"common", name}, path
