"""studies/ layout: the paper's fixed choices (studies._paper) agree with the bumper law's
declared defaults where both hold one, reproduce the paper's own numbers, and no recipe
imports another recipe."""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

from engine.impact import LAWS
from engine.units import KN_PER_MM
from pipeline.grid import BASELINE
from studies import _paper as paper

STUDIES = Path(__file__).resolve().parents[2] / "studies"
SHARED = {"__init__", "_paper", "_plot", "_recipe", "_peaks_vs_gap", "_options",
          "_code_suite", "_design_search", "_design_space", "_design_archive",
          "_suite_archive", "_suite_verdicts", "_suite_figure", "_plan_verdicts"}


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


def _studies_imports(path: Path) -> set[str]:
    """Modules of studies/ a module imports (relative or absolute)."""
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            if node.level == 1:
                found |= {node.module} if node.module else {a.name for a in node.names}
            elif node.module and node.module.startswith("studies"):
                rest = node.module.split(".")[1:]
                found |= set(rest[:1]) if rest else {a.name for a in node.names}
        elif isinstance(node, ast.Import):
            found |= {a.name.split(".")[1] for a in node.names
                      if a.name.startswith("studies.")}
    return found


@pytest.mark.parametrize("path", sorted(STUDIES.glob("*.py")), ids=lambda p: p.stem)
def test_no_recipe_imports_another(path):
    """Recipes (and the general sweep) import only the shared underscore modules."""
    assert _studies_imports(path) <= SHARED, path.stem
