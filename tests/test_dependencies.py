"""Every package that the code or a config needs is declared in pyproject.toml.

A fresh clone in a new environment installs only what pyproject.toml declares (README, .ci/run);
a module that imports, or a config that composes, anything else works only on the machine where
it happened to be installed. Three checks:

1. statically, every import in sim/, surrogate/, studies/ (and benchmarks/, tests/) maps to a
   distribution that pyproject.toml declares: module-level imports of the packages to the core
   dependencies, imports inside functions (optional features) to the core or an extra, tests to
   the core or the ``test`` extra; a package imported directly must be declared even when
   another dependency happens to pull it in;
2. every module of the packages imports in this environment;
3. every config group option composes, the Hydra launchers included, and each launcher's
   ``_target_`` class imports.
"""
import ast
import importlib
import importlib.metadata as md
import re
import sys
import tomllib
from pathlib import Path

import pytest
from hydra import compose, initialize_config_dir
from hydra.utils import get_class

import sim

REPO = Path(__file__).resolve().parents[1]
PACKAGES = ["sim", "surrogate", "studies"]
LOCAL = {*PACKAGES, "tests", "benchmarks"}


def _name(requirement):
    """Normalised distribution name of a PEP 508 requirement string."""
    return re.sub(r"[-_.]+", "-", re.match(r"\s*([A-Za-z0-9_.\-]+)", requirement).group(1)).lower()


PYPROJECT = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]
CORE = {_name(r) for r in PYPROJECT["dependencies"]}
EXTRAS = {extra: {_name(r) for r in reqs} for extra, reqs in PYPROJECT["optional-dependencies"].items()}
ANY_EXTRA = set().union(*EXTRAS.values())
DISTRIBUTIONS = {module: {_name(d) for d in dists} for module, dists in md.packages_distributions().items()}


def _imports(path):
    """(top-level module, imported at module level) for every absolute import of a file."""
    tree = ast.parse(path.read_text(), filename=str(path))
    top = {id(node) for node in tree.body}
    for stmt in tree.body:  # imports under a module-level `if`/`try` count as module level too
        if isinstance(stmt, (ast.If, ast.Try)):
            top |= {id(n) for n in ast.walk(stmt)}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield alias.name.split(".")[0], id(node) in top
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            yield node.module.split(".")[0], id(node) in top


def _third_party(paths):
    for path in paths:
        for module, module_level in _imports(path):
            if module in sys.stdlib_module_names or module in LOCAL or module == "__future__":
                continue
            yield path.relative_to(REPO), module, module_level


def _files(*folders):
    return [p for folder in folders for p in sorted((REPO / folder).rglob("*.py"))]


@pytest.mark.parametrize("folder", [*PACKAGES, "benchmarks"])
def test_package_imports_are_declared(folder):
    """Module-level imports need a core dependency; function-local ones (optional features) an extra."""
    missing = []
    for path, module, module_level in _third_party(_files(folder)):
        dists = DISTRIBUTIONS.get(module)
        allowed = CORE if module_level else CORE | ANY_EXTRA
        if module == "torch" and not module_level:
            # the gp extra is optional and need not be installed to run this check
            dists = dists or {"torch"}
        if not dists or not dists & allowed:
            missing.append(f"{path}: import {module} (distribution {sorted(dists or ['not installed'])})")
    assert not missing, "imports without a declared dependency in pyproject.toml:\n" + "\n".join(missing)


def test_test_imports_are_declared():
    """Tests may use the core and the ``test`` extra, the packages that `pip install -e .[test]` installs."""
    allowed = CORE | EXTRAS["test"]
    missing = [f"{path}: import {module}" for path, module, _ in _third_party(_files("tests"))
               if not (DISTRIBUTIONS.get(module, set()) & allowed)]
    assert not missing, "test imports without a declared dependency:\n" + "\n".join(missing)


@pytest.mark.parametrize("module", sorted(
    ".".join(p.relative_to(REPO).with_suffix("").parts).removesuffix(".__init__")
    for folder in PACKAGES for p in (REPO / folder).rglob("*.py")))
def test_every_module_imports(module):
    importlib.import_module(module)


LAUNCHERS = sorted(p.stem for p in (sim.CONF_DIR / "hydra" / "launcher").glob("*.yaml"))


@pytest.mark.parametrize("launcher", LAUNCHERS)
def test_every_launcher_composes_and_its_plugin_imports(launcher):
    """hydra/launcher=parallel (joblib, core dependency) and =slurm (submitit, the slurm extra)."""
    with initialize_config_dir(config_dir=str(sim.CONF_DIR), version_base="1.3"):
        cfg = compose("config", overrides=[f"hydra/launcher={launcher}"], return_hydra_config=True)
    get_class(cfg.hydra.launcher._target_)


def test_every_config_group_composes():
    """Each option of each group under conf/ (study and experiment included) composes."""
    groups = [d for d in sorted(sim.CONF_DIR.iterdir()) if d.is_dir() and d.name not in ("hydra", "local")]
    assert {d.name for d in groups} >= {"bearing", "lubricant", "load", "solver", "study", "experiment"}
    with initialize_config_dir(config_dir=str(sim.CONF_DIR), version_base="1.3"):
        for group in groups:
            for option in sorted(group.glob("*.yaml")):
                compose("config", overrides=[f"+{group.name}={option.stem}"]) if group.name in (
                    "experiment", "variant", "study") else compose("config", overrides=[f"{group.name}={option.stem}"])
