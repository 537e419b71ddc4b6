"""Architecture rules of the three import packages, checked on their source.

The rules (docs/architecture.md):

* no import loop inside ``analytic``, ``skfem_dielectric`` or ``validation`` (module-level
  and function-level imports alike);
* ``analytic`` and ``skfem_dielectric`` never import each other or ``validation`` (the
  FE-versus-theory cross-check must be able to catch a bug on either side);
* in ``skfem_dielectric`` every module belongs to a layer (:data:`LAYERS`, bottom up) and
  imports only from its own group and from the layers below it: two groups of one layer
  (``models`` and ``solvers``, say) never import each other, and nothing below ``gallery``
  imports ``models``, ``gallery`` or ``studies``; a module's size follows from what it is
  responsible for, not from a line cap;
* no import of a private name (``_x``) from another module, and no use of another
  module's private attribute through its name (``module._x``);
* imports at module level only, except for optional dependencies (the ``fast`` and
  ``cluster`` extras), which are imported where they are used;
* every module file of ``skfem_dielectric`` is named in docs/architecture.md;
* in ``validation`` the same layer rule with :data:`VALIDATION_LAYERS`: the specs, cases,
  tables and the result store import neither the FE runner, the figures nor the studies,
  and importing them loads no finite elements (neither ``skfem_dielectric`` nor
  scikit-fem); every module file of ``validation`` is named in the validation section of
  docs/architecture.md;
* the top level of ``skfem_dielectric`` is the short list of names a user of the paper's
  plates needs (its ``__all__``) plus its modules and subpackages as namespaces: every name
  of the top-level ``__all__`` and of each subpackage's ``__all__`` resolves, and the top
  level binds no other name, so that the cut cannot grow back unnoticed.

Each rule reports every offending place, so that a failure says what to change.
"""

from __future__ import annotations

import ast
import importlib
import os
import pkgutil
import subprocess
import sys
import types
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PACKAGES = ("analytic", "skfem_dielectric", "validation")
# optional dependencies (extras): imported inside the functions that need them
OPTIONAL = ("pypardiso", "mkl", "dask", "distributed", "bokeh", "tornado")
#: the layers of ``skfem_dielectric``, bottom up; the groups of one layer stand side by side
#: (neither imports the other).  A group is a top-level module or a subpackage; the package
#: itself (``skfem_dielectric/__init__.py``) sits above all of them and re-exports them.
LAYERS = (
    ("checks", "kinematics"),        # argument checks, tensor algebra of small matrices
    ("fem", "materials"),            # discretisation machinery; constitutive laws
    ("forms", "linalg"),             # weak forms; linear solvers, symmetric storage, inertia
    ("problem",),                    # the contract every model implements
    ("stability", "export"),         # stability of a converged state; VTU/XDMF output
    ("models", "solvers"),           # the FE models; Newton, ramp, continuation, critical load
    ("gallery",),                    # the paper's plates: builders, drivers, load paths
    ("studies",),                    # the paper's analyses: model + solver + stability
    ("skfem_dielectric",),           # the package namespace
)
#: the layers of ``validation``, bottom up, in the same sense as :data:`LAYERS`; the groups
#: below ``fe`` import no finite elements
VALIDATION_LAYERS = (
    ("clash", "progress", "specs", "records",   # package guard, progress; run data and the
     "markers"),                     # location tolerance, records; the markers' vocabulary
    ("data",),                       # the measured tables and their readers, no FE
    ("cases",),                      # the validation cases, one per paper figure
    ("table", "checker"),            # the tidy CSV of a case; scores of another code's CSVs
    ("store",),                      # lock, atomic files, checksums, resume
    ("fe", "figures"),               # the FE runner; the paper's figures
    ("options", "cluster"),          # checks of the command-line options; the dask cluster
    ("studies",),                    # buckling, post-buckling, wrinkling, snap-through
    ("clamp_zone",),                 # the clamp-zone study: runners, tables, figures, command
    ("results", "report", "explore",   # case summaries; summary.json, report.md; the page;
     "check_report"),                # the figures and files of `check`
    ("sweep",),                      # the harness: run_case, run_cases, validate
    ("cli",),                        # the command line
    ("validation",),                 # the package namespace
)
#: the modules of subpackages that are groups of their own
_SUBGROUPS = {g for groups in VALIDATION_LAYERS for g in groups if "." in g}
#: the groups of ``validation`` that import no finite elements
VALIDATION_NO_FE = tuple(g for groups in VALIDATION_LAYERS[:5] for g in groups)


def _modules(package: str) -> dict[str, Path]:
    out = {}
    for path in sorted((ROOT / package).rglob("*.py")):
        rel = path.relative_to(ROOT).with_suffix("")
        parts = list(rel.parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


ALL = {name: path for pkg in PACKAGES for name, path in _modules(pkg).items()}
TREES = {name: ast.parse(path.read_text(), filename=str(path)) for name, path in ALL.items()}


def _is_package(module: str) -> bool:
    return ALL[module].name == "__init__.py"


def _resolve(module: str, node: ast.ImportFrom) -> str:
    """Absolute name of the module an ``ImportFrom`` reads from."""
    if not node.level:
        return node.module or ""
    base = module.split(".")
    if not _is_package(module):
        base = base[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def _imports(module: str):
    """``(node, target_module, imported_names)`` of every import in ``module``."""
    for node in ast.walk(TREES[module]):
        if isinstance(node, ast.Import):
            for a in node.names:
                yield node, a.name, []
        elif isinstance(node, ast.ImportFrom):
            target = _resolve(module, node)
            names = [a.name for a in node.names]
            yield node, target, names


def _edges(module: str) -> set[str]:
    """Modules of the three packages that ``module`` imports."""
    out = set()
    for _, target, names in _imports(module):
        for name in names or [None]:
            sub = f"{target}.{name}" if name else None
            if sub in ALL:
                out.add(sub)
            elif target in ALL:
                out.add(target)
    out.discard(module)
    return out


def _cycles(package: str) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan)."""
    nodes = [m for m in ALL if m.split(".")[0] == package]
    graph = {m: sorted(e for e in _edges(m) if e.split(".")[0] == package) for m in nodes}
    index, low, stack, on, comps, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                comps.append(sorted(comp))

    for v in nodes:
        if v not in index:
            visit(v)
    return comps


def _where(module: str, node: ast.AST) -> str:
    return f"{ALL[module].relative_to(ROOT)}:{node.lineno}"


@pytest.mark.parametrize("package", PACKAGES)
def test_no_import_loop(package):
    cycles = _cycles(package)
    assert not cycles, "import loops: " + "; ".join(" <-> ".join(c) for c in cycles)


def test_theory_and_fe_stay_independent():
    bad = []
    for module in ALL:
        pkg = module.split(".")[0]
        forbidden = {"analytic": ("skfem_dielectric", "validation"),
                     "skfem_dielectric": ("analytic", "validation"),
                     "validation": ()}[pkg]
        for node, target, _ in _imports(module):
            if target.split(".")[0] in forbidden:
                bad.append(f"{_where(module, node)} imports {target}")
    assert not bad, "\n".join(bad)


def _private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def test_no_private_name_imported_from_another_module():
    bad = []
    for module in ALL:
        for node, target, names in _imports(module):
            for name in names:
                if _private(name):
                    bad.append(f"{_where(module, node)} imports {name} from {target}")
    assert not bad, "\n".join(bad)


def test_no_private_attribute_of_another_module():
    """``mod._x`` where ``mod`` is a module imported by name (``import a.b as mod``)."""
    bad = []
    for module, tree in TREES.items():
        aliases = set()
        for node, target, names in _imports(module):
            if isinstance(node, ast.Import):
                aliases.update(a.asname or a.name.split(".")[0] for a in node.names)
            else:
                aliases.update(a.asname or a.name for a in node.names
                               if f"{target}.{a.name}" in ALL)
        for node in ast.walk(tree):
            if (isinstance(node, ast.Attribute) and _private(node.attr)
                    and isinstance(node.value, ast.Name) and node.value.id in aliases):
                bad.append(f"{_where(module, node)} uses {node.value.id}.{node.attr}")
    assert not bad, "\n".join(bad)


def test_imports_at_module_level_except_optional_dependencies():
    bad = []
    for module, tree in TREES.items():
        top = set(map(id, tree.body))
        for stmt in tree.body:   # module-level try/if/with blocks are module level too
            if isinstance(stmt, (ast.Try, ast.If, ast.With)):
                top.update(id(n) for n in ast.walk(stmt)
                           if isinstance(n, (ast.Import, ast.ImportFrom)))
        for node, target, _ in _imports(module):
            if id(node) in top:
                continue
            if target.split(".")[0] in OPTIONAL:
                continue
            bad.append(f"{_where(module, node)} imports {target} inside a function")
    assert not bad, "\n".join(bad)


def _group(module: str) -> str | None:
    """Layer group of a module of a package: its top-level module or subpackage, or a
    module of a subpackage that a layer names itself (``"pkg.module"``; none now)."""
    parts = module.split(".")
    if len(parts) > 2 and ".".join(parts[1:3]) in _SUBGROUPS:
        return ".".join(parts[1:3])
    return parts[1] if len(parts) > 1 else parts[0]


def _layer(group: str, layers=LAYERS) -> int | None:
    for i, groups in enumerate(layers):
        if group in groups:
            return i
    return None


def _layer_violations(package: str = "skfem_dielectric", layers=LAYERS) -> list[str]:
    """Every import of ``package`` that goes sideways or up its ``layers``."""
    bad = []
    for module in ALL:
        if module.split(".")[0] != package:
            continue
        group = _group(module)
        layer = _layer(group, layers)
        if layer is None:
            bad.append(f"{ALL[module].relative_to(ROOT)}: {module} is in no layer "
                       f"(group {group!r}); add it to the layers and docs/architecture.md")
            continue
        allowed = {g for groups in layers[:layer] for g in groups} | {group}
        for node, target, names in _imports(module):
            if target.split(".")[0] != package:
                continue
            for name in names or [None]:
                sub = f"{target}.{name}" if name else None
                dest = sub if sub in ALL else target
                if dest == module or _group(dest) in allowed:
                    continue
                where = "up" if (_layer(_group(dest), layers) or 0) > layer else "sideways"
                bad.append(f"{_where(module, node)}: {module} ({group}) imports {dest} "
                           f"({_group(dest)}), {where} the layers; {group} may import "
                           f"{', '.join(sorted(allowed - {group}))} and itself")
    return bad


def test_imports_follow_the_layers():
    bad = _layer_violations()
    assert not bad, "\n".join(bad)


def test_validation_imports_follow_its_layers():
    bad = _layer_violations("validation", VALIDATION_LAYERS)
    assert not bad, "\n".join(bad)


def test_validation_cases_import_no_finite_elements():
    """Importing the specs, cases, tables and the store loads neither ``skfem_dielectric``
    nor scikit-fem (``skfem-dielectric list`` and the tables need no FE)."""
    modules = sorted(m for m in ALL if m.split(".")[0] == "validation"
                     and _group(m) in VALIDATION_NO_FE)
    assert "validation.cases" in modules and "validation.specs" in modules
    code = ("import sys\n" + "".join(f"import {m}\n" for m in modules)
            + "print(sorted(m for m in sys.modules if m.split('.')[0] in "
              "('skfem_dielectric', 'skfem')))")
    env = {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=ROOT, env=env, check=True).stdout
    assert out.strip() == "[]", f"importing {', '.join(modules)} loads {out.strip()}"


def _undocumented(package: str, text: str) -> list[str]:
    """The module files of ``package`` that ``text`` does not name."""
    missing = []
    for module, path in ALL.items():
        if module.split(".")[0] != package:
            continue
        rel = path.relative_to(ROOT / package)
        name = f"{rel.parent.as_posix()}/" if rel.name == "__init__.py" else rel.as_posix()
        if name != "./" and f"`{name}`" not in text:
            missing.append(name)
    return missing


def test_every_module_is_in_docs_architecture():
    text = (ROOT / "docs" / "architecture.md").read_text()
    missing = _undocumented("skfem_dielectric", text)
    assert not missing, "docs/architecture.md does not name: " + ", ".join(missing)


def test_every_validation_module_is_in_its_docs_section():
    text = (ROOT / "docs" / "architecture.md").read_text()
    head = "## The layers of `validation`"
    assert head in text, f"docs/architecture.md has no section {head!r}"
    section = text.split(head, 1)[1].split("\n## ", 1)[0]
    missing = _undocumented("validation", section)
    assert not missing, f"{head} in docs/architecture.md does not name: " + ", ".join(missing)


def test_the_checker_sees_a_layer_violation(monkeypatch):
    """A solver importing a model, and a model importing a solver, are reported."""
    pkg = ROOT / "skfem_dielectric"       # paths only named in the messages, never read
    fake = {"skfem_dielectric": pkg / "__init__.py",
            "skfem_dielectric.solvers": pkg / "solvers" / "__init__.py",
            "skfem_dielectric.solvers.newton": pkg / "solvers" / "newton.py",
            "skfem_dielectric.models": pkg / "models" / "__init__.py",
            "skfem_dielectric.models.membrane": pkg / "models" / "membrane.py",
            "skfem_dielectric.problem": pkg / "problem.py"}
    trees = {name: ast.parse("") for name in fake}
    trees["skfem_dielectric.solvers.newton"] = ast.parse("from ..models import membrane\n"
                                                         "from ..problem import Problem\n")
    trees["skfem_dielectric.models.membrane"] = ast.parse("from ..solvers.newton import newton\n")
    monkeypatch.setitem(globals(), "ALL", fake)
    monkeypatch.setitem(globals(), "TREES", trees)
    bad = _layer_violations()
    assert len(bad) == 2, bad
    assert "skfem_dielectric.solvers.newton (solvers) imports skfem_dielectric.models.membrane" \
        " (models), sideways" in bad[0]
    assert "skfem_dielectric.models.membrane (models) imports skfem_dielectric.solvers.newton" \
        " (solvers), sideways" in bad[1]


def test_the_checker_sees_a_loop_and_a_private_import(tmp_path, monkeypatch):
    """The rules can fail: a two-module loop and a private import are reported."""
    a = ast.parse("from .b import f\nfrom .b import _g\n")
    b = ast.parse("from .a import h\n")
    fake = {"pkg": tmp_path / "pkg" / "__init__.py", "pkg.a": tmp_path / "pkg" / "a.py",
            "pkg.b": tmp_path / "pkg" / "b.py"}
    monkeypatch.setitem(globals(), "ALL", fake)
    monkeypatch.setitem(globals(), "TREES", {"pkg": ast.parse(""), "pkg.a": a, "pkg.b": b})
    assert _cycles("pkg") == [["pkg.a", "pkg.b"]]
    names = [n for _, _, ns in _imports("pkg.a") for n in ns]
    assert [n for n in names if _private(n)] == ["_g"]


def test_the_checker_sees_cases_importing_the_fe_runner(monkeypatch):
    """``validation.cases`` importing the FE runner is reported as going up the layers."""
    pkg = ROOT / "validation"             # paths only named in the messages, never read
    fake = {"validation": pkg / "__init__.py", "validation.cases": pkg / "cases.py",
            "validation.fe": pkg / "fe" / "__init__.py",
            "validation.fe.model": pkg / "fe" / "model.py"}
    trees = {name: ast.parse("") for name in fake}
    trees["validation.cases"] = ast.parse("from .fe.model import with_dead_load\n")
    monkeypatch.setitem(globals(), "ALL", fake)
    monkeypatch.setitem(globals(), "TREES", trees)
    bad = _layer_violations("validation", VALIDATION_LAYERS)
    assert len(bad) == 1, bad
    assert "validation.cases (cases) imports validation.fe.model (fe), up the layers" in bad[0]


def _unresolved(module: types.ModuleType) -> list[str]:
    """The names of ``module.__all__`` that are not attributes of ``module``."""
    return [name for name in getattr(module, "__all__", ()) if not hasattr(module, name)]


def _unlisted(module: types.ModuleType) -> list[str]:
    """The names ``module`` binds besides its ``__all__``, its own submodules and dunders."""
    listed = set(module.__all__)
    return sorted(name for name, value in vars(module).items()
                  if name not in listed and not (name.startswith("__") and name.endswith("__"))
                  and not (isinstance(value, types.ModuleType)
                           and value.__name__ == f"{module.__name__}.{name}"))


def test_the_top_level_names_resolve_and_nothing_else_is_exported():
    """The top-level ``__all__`` and every subpackage's ``__all__`` resolve; the top level
    binds nothing outside its ``__all__`` but its modules and subpackages."""
    import skfem_dielectric
    bad = [f"skfem_dielectric.{name}" for name in _unresolved(skfem_dielectric)]
    for info in pkgutil.walk_packages(skfem_dielectric.__path__, "skfem_dielectric."):
        if info.ispkg:
            package = importlib.import_module(info.name)
            bad += [f"{info.name}.{name}" for name in _unresolved(package)]
    assert not bad, "names in __all__ that do not resolve: " + ", ".join(bad)
    extra = _unlisted(skfem_dielectric)
    assert not extra, "skfem_dielectric binds names outside its __all__: " + ", ".join(extra)


def test_the_checker_sees_an_unlisted_and_an_unresolved_name():
    """A re-export missing from ``__all__`` and an ``__all__`` entry without an object are
    reported; a submodule bound by the import system is not."""
    package = types.ModuleType("pkg")
    package.__all__ = ["solve", "missing"]
    package.solve = len
    package.helper = len                            # re-exported but not listed
    package.sub = types.ModuleType("pkg.sub")       # its own submodule: a namespace
    package.np = types.ModuleType("numpy")          # another package's module: a leak
    assert _unresolved(package) == ["missing"]
    assert _unlisted(package) == ["helper", "np"]
