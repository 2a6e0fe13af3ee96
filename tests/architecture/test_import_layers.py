"""The package's layers (docs/architecture.md, STYLE.md "Module boundaries"): every import of a
project module, function-local ones included, points to the same or a lower layer, the
import graph has no cycle, and the numerical core imports no config, I/O or search library.
"""
import ast
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
PACKAGES = ("sim", "studies", "surrogate")

# (module prefix, layer): the longest matching prefix decides; lower numbers are lower layers
LAYERS = [
    ("sim.errors", 0), ("sim.config_schema", 0), ("sim._math", 0),
    ("sim.geometry", 1),
    ("sim.physics", 2),
    ("sim.solvers", 3),
    ("sim.io", 4),
    ("sim.api", 5),
    ("sim", 6), ("sim.run", 6),
    ("surrogate", 7), ("studies", 8),
]
# what the numerical core (layers 0-3) must never import
CORE_FORBIDDEN = ("hydra", "omegaconf", "optuna", "xarray", "sklearn", "netCDF4", "matplotlib")
# studies and surrogates use the public API only: the package facade, sim.api and sim.io
PUBLIC = ("sim", "sim.api", "sim.io")


def layer(module):
    best = max((p for p, _ in LAYERS if module == p or module.startswith(p + ".")), key=len)
    return dict(LAYERS)[best]


def module_name(path):
    parts = list(path.relative_to(REPO).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = {module_name(p): p for pkg in PACKAGES for p in sorted((REPO / pkg).rglob("*.py"))}


def imports(module):
    """(imported module, line) for every import statement in ``module``, at any depth."""
    tree = ast.parse(MODULES[module].read_text())
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(a.name, node.lineno) for a in node.names]
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            for a in node.names:  # ``from sim import io`` imports the submodule sim.io
                sub = f"{node.module}.{a.name}"
                found.append((sub if sub in MODULES else node.module, node.lineno))
    return found


def project_imports(module):
    return [(m, line) for m, line in imports(module) if m.split(".")[0] in PACKAGES and m in MODULES]


def test_every_module_is_assigned_a_layer():
    assert len(MODULES) > 30
    for m in MODULES:
        layer(m)


@pytest.mark.parametrize("module", sorted(MODULES))
def test_no_upward_import(module):
    up = [f"{module} (layer {layer(module)}) imports {m} (layer {layer(m)}) at line {line}"
          for m, line in project_imports(module) if layer(m) > layer(module)]
    assert not up, "\n".join(up)


@pytest.mark.parametrize("module", sorted(m for m in MODULES if layer(m) <= 3))
def test_numerical_core_imports_no_config_io_or_search_library(module):
    bad = [f"{module} imports {m} at line {line}" for m, line in imports(module) if m.split(".")[0] in CORE_FORBIDDEN]
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("module", sorted(m for m in MODULES if m.split(".")[0] in ("studies", "surrogate")))
def test_studies_use_only_the_public_api(module):
    private = [f"{module} imports {m} at line {line}" for m, line in project_imports(module)
               if m.startswith("sim") and not any(m == p or m.startswith(p + ".") and p != "sim" for p in PUBLIC)]
    assert not private, "\n".join(private)


def find_cycle(graph):
    """A list of modules forming a cycle in ``graph`` (module -> imported modules), or None."""
    state = {}

    def visit(m, path):
        if state.get(m) == "done":
            return None
        if state.get(m) == "open":
            return path[path.index(m):] + [m]
        state[m] = "open"
        for t in graph.get(m, []):
            cycle = visit(t, path + [m])
            if cycle:
                return cycle
        state[m] = "done"
        return None

    for m in graph:
        cycle = visit(m, [])
        if cycle:
            return cycle
    return None


def test_import_graph_has_no_cycle():
    graph = {m: sorted({t for t, _ in project_imports(m) if t != m}) for m in MODULES}
    cycle = find_cycle(graph)
    assert cycle is None, " -> ".join(cycle)


def test_cycle_finder_finds_a_cycle_and_layers_order_as_documented():
    assert find_cycle({"a": ["b"], "b": ["c"], "c": ["a"], "d": ["a"]}) in (["a", "b", "c", "a"],)
    assert find_cycle({"a": ["b"], "b": [], "c": ["a", "b"]}) is None
    assert layer("sim._math.roots") < layer("sim.geometry") < layer("sim.physics.friction") \
        < layer("sim.solvers.kinematics") < layer("sim.io") < layer("sim.api.simulation") < layer("studies.loop")
