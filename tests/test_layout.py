"""The code's layout, kept true: data flows one way (engine <- pipeline <- studies), and inside
pipeline/ through its packages in order (PIPELINE_LEVELS), no import circle (imports inside
functions counted), no private name imported from another module, no
constant written twice, no module over 500 lines, and the map of the code in docs/model.md the
one the packages' docstrings give (tools/code_map.py writes it)."""
import ast
import importlib.util
import sys
from collections import defaultdict
from pathlib import Path

import pytest

PROJECT = Path(__file__).resolve().parents[1]
PACKAGES = ("engine", "pipeline", "studies")
MAX_LINES = 500


def modules() -> dict[str, Path]:
    """Dotted name -> file of every module of the three packages."""
    found = {}
    for package in PACKAGES:
        for path in sorted((PROJECT / package).rglob("*.py")):
            parts = path.relative_to(PROJECT).with_suffix("").parts
            if parts[-1] == "__init__":
                parts = parts[:-1]
            found[".".join(parts)] = path
    return found


MODULES = modules()
TREES = {name: ast.parse(path.read_text(), str(path)) for name, path in MODULES.items()}


def imports(name: str, tree: ast.Module):
    """(line, imported module, names taken) of every import of module `name`, at any depth
    (inside functions too), resolved to the project's modules."""
    package = name if MODULES[name].name == "__init__.py" else name.rpartition(".")[0]
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] in PACKAGES:
                    yield node.lineno, alias.name, ()
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[:len(base) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.split(".")[0] not in PACKAGES:
                continue
            taken = [alias.name for alias in node.names]
            submodules = [f"{target}.{n}" for n in taken if f"{target}.{n}" in MODULES]
            if submodules:
                for sub in submodules:
                    yield node.lineno, sub, ()
                rest = tuple(n for n in taken if f"{target}.{n}" not in MODULES)
                if rest:
                    yield node.lineno, target, rest
            else:
                yield node.lineno, target, tuple(taken)


EDGES = {name: list(imports(name, tree)) for name, tree in TREES.items()}


def test_data_flows_one_way():
    order = {package: rank for rank, package in enumerate(PACKAGES)}
    wrong = [f"{name}:{line} imports {target}" for name, edges in EDGES.items()
             for line, target, _ in edges
             if order[target.split(".")[0]] > order[name.split(".")[0]]]
    assert not wrong, "\n".join(wrong)


PIPELINE_LEVELS = (
    ("records and the shared leaves", ("pipeline.records", "pipeline.errors", "pipeline.checks",
                                       "pipeline.writing", "pipeline.building_file",
                                       "pipeline.progress")),
    ("motions", ("pipeline.motions",)),
    ("grid and execute", ("pipeline.members", "pipeline.grid", "pipeline.listed",
                          "pipeline.provenance", "pipeline.cluster", "pipeline.execute")),
    ("archive", ("pipeline.archive", "pipeline.suite_labels",
                 # the stores write the archive (its labels given what assess computes)
                 "pipeline.execute.netcdf_store", "pipeline.execute.zarr_store")),
    ("assess", ("pipeline.assess",)),
    ("orchestration", ("pipeline", "pipeline.orchestration", "pipeline.histories")),
)
"""The packages of pipeline/ in the order data flows through them, level by level: a module
imports only from its own level or those before it (what a result means, assess, never reaches
back into the motions; the archive labels what assess computes without importing it). A
module is placed by its longest entry (a package's entry places its modules, the package
`pipeline` itself only its own face)."""


def pipeline_level(name: str) -> tuple[int, str]:
    """(rank, level name) of pipeline module `name` in PIPELINE_LEVELS; (-1, "") when no entry
    places it."""
    found = [(len(entry), rank, level) for rank, (level, entries) in enumerate(PIPELINE_LEVELS)
             for entry in entries
             if name == entry or (entry != "pipeline" and name.startswith(entry + "."))]
    if not found:
        return -1, ""
    _, rank, level = max(found)
    return rank, level


def test_every_pipeline_module_has_a_level():
    unplaced = [name for name in MODULES
                if name.split(".")[0] == "pipeline" and pipeline_level(name)[0] < 0]
    assert not unplaced, ("pipeline modules missing from PIPELINE_LEVELS (place each at the "
                          "level of what it holds): " + ", ".join(unplaced))


def test_pipeline_packages_import_in_order():
    wrong = []
    for name, edges in EDGES.items():
        if name.split(".")[0] != "pipeline":
            continue
        rank, level = pipeline_level(name)
        for line, target, _ in edges:
            if target.split(".")[0] != "pipeline":
                continue
            target_rank, target_level = pipeline_level(target)
            if target_rank > rank:
                wrong.append(f"{name}:{line} ({level}) imports {target} ({target_level}), a "
                             "later level")
    assert not wrong, ("pipeline's order is " + " -> ".join(level for level, _ in
                                                         PIPELINE_LEVELS) + "\n"
                       + "\n".join(wrong))


def test_no_import_circle():
    graph = defaultdict(set)
    for name, edges in EDGES.items():
        for _, target, _ in edges:
            if target in MODULES and target != name:
                graph[name].add(target)
    circles, state = [], {}

    def visit(node, path):
        state[node] = "open"
        for nxt in sorted(graph[node]):
            if state.get(nxt) == "open":
                circles.append(" -> ".join(path[path.index(nxt):] + [nxt]))
            elif nxt not in state:
                visit(nxt, path + [nxt])
        state[node] = "done"

    sys.setrecursionlimit(10_000)
    for node in sorted(MODULES):
        if node not in state:
            visit(node, [node])
    assert not circles, "\n".join(circles)


def test_no_private_name_imported_from_another_module():
    private = [f"{name}:{line} takes {', '.join(n for n in taken if n.startswith('_'))} "
               f"from {target}" for name, edges in EDGES.items()
               for line, target, taken in edges
               if target != name and any(n.startswith("_") for n in taken)]
    assert not private, "\n".join(private)


def test_no_module_over_500_lines():
    long = {name: n for name, path in MODULES.items()
            if (n := len(path.read_text().splitlines())) > MAX_LINES}
    assert not long, long


DECLARATIONS = frozenset({"ORDER", "NAME"})
"""Names each module of a registry declares for itself (a law's or a rule's place in its
listing, its name there: an isolator and a story may both be "bilinear", each in its own
registry): one declaration each, not a fact written twice."""


def constants(tree: ast.Module):
    """(name, value) of the module-level UPPER_CASE constants given as literals (registry
    declarations aside)."""
    for node in tree.body:
        if isinstance(node, ast.Assign) and len(node.targets) == 1 \
                and isinstance(node.targets[0], ast.Name):
            name = node.targets[0].id
            if name.isupper() and not name.startswith("_") and name not in DECLARATIONS:
                try:
                    yield name, repr(ast.literal_eval(node.value))
                except ValueError:
                    continue


def test_no_constant_written_twice():
    where = defaultdict(list)
    for module, tree in TREES.items():
        for name, value in constants(tree):
            where[name, value].append(module)
    twice = {f"{name} = {value}": found for (name, value), found in where.items()
             if len(found) > 1}
    assert not twice, twice


def test_the_map_of_the_code_is_the_packages_own():
    spec = importlib.util.spec_from_file_location("code_map", PROJECT / "tools" / "code_map.py")
    code_map = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(code_map)
    text = (PROJECT / "docs" / "model.md").read_text()
    expected = code_map.table(PROJECT)
    if expected not in text:
        pytest.fail("docs/model.md's map of the code is out of date with the packages' "
                    "docstrings: run `python tools/code_map.py --write`")
