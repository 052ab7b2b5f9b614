"""The package's layers hold (issue 23): no import cycle between modules, and no import
that runs up the layers docs/ARCHITECTURE.md draws.  Imports inside functions count: they
hid four cycles once."""

from __future__ import annotations

import ast
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent / "workbook_gen"

#: Lowest first; a unit (a top-level module or package) imports only from its own layer
#: or below (docs/ARCHITECTURE.md, The four pipelines: "Layers, lowest first").
LAYERS = [
    {"xlerror", "errors", "cellref", "version", "progress", "terminate", "forked", "files",
     "names"},
    {"xlmath"},
    {"expr", "formula"},
    {"mechanisms", "xlsx", "evaluator", "engines"},
    {"scene", "pruning", "reference"},
    {"tabulate"},
    {"workbook"},
    {"auditor"},
    {"batching", "tradeoff"},
    {"cli", "(root)"},
]
RANK = {unit: i for i, layer in enumerate(LAYERS) for unit in layer}


def _name(path: Path) -> str:
    parts = list(path.relative_to(ROOT.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _graph() -> dict[str, set[str]]:
    modules = {_name(p): p for p in ROOT.rglob("*.py")}
    edges: dict[str, set[str]] = defaultdict(set)
    for name, path in modules.items():
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom):
                if node.level:
                    base = package.split(".")[:len(package.split(".")) - node.level + 1]
                    target = ".".join(base + ([node.module] if node.module else []))
                else:
                    target = node.module or ""
                for alias in node.names:
                    sub = f"{target}.{alias.name}"
                    found = sub if sub in modules else target
                    if found in modules:
                        edges[name].add(found)
            elif isinstance(node, ast.Import):
                edges[name].update(a.name for a in node.names if a.name in modules)
        edges.setdefault(name, set())
    return edges


def _unit(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "(root)"


def _cycles(edges: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected parts of more than one module (Tarjan, iteratively)."""
    index, low, stack, on, found, counter = {}, {}, [], set(), [], [0]
    for start in edges:
        if start in index:
            continue
        work = [(start, iter(sorted(edges[start])))]
        index[start] = low[start] = counter[0]
        counter[0] += 1
        stack.append(start)
        on.add(start)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = counter[0]
                    counter[0] += 1
                    stack.append(child)
                    on.add(child)
                    work.append((child, iter(sorted(edges[child]))))
                elif child in on:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                part = []
                while True:
                    top = stack.pop()
                    on.discard(top)
                    part.append(top)
                    if top == node:
                        break
                if len(part) > 1:
                    found.append(sorted(part))
    return found


def test_no_import_cycle():
    assert _cycles(_graph()) == []


def test_every_unit_has_a_layer():
    units = {_unit(m) for m in _graph()}
    assert units - set(RANK) == set(), "units missing from LAYERS (and ARCHITECTURE.md)"


def test_no_import_runs_up_the_layers():
    up = sorted({(_unit(a), _unit(b)) for a, targets in _graph().items() for b in targets
                 if RANK[_unit(b)] > RANK[_unit(a)]})
    assert up == []


def test_the_cycle_finder_finds_a_cycle():
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]


# -- private names stay in their package ------------------------------------------------------

TREES = [ROOT, ROOT.parent / "bench", ROOT.parent / "scripts"]


def _private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def _dotted(path: Path, top: Path = ROOT.parent) -> tuple[str, str]:
    """(the module's dotted name, its package's): ``workbook_gen.auditor.pipeline`` is in
    ``workbook_gen.auditor``, a package's ``__init__`` in the package itself; a script of
    bench/ or scripts/ in ``bench`` or ``scripts``."""
    parts = list(path.relative_to(top).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
        return ".".join(parts), ".".join(parts)
    return ".".join(parts), ".".join(parts[:-1])


def _modules() -> dict[str, Path]:
    return {_dotted(p)[0]: p for tree in TREES for p in sorted(tree.rglob("*.py"))}


def _package_of(module: str, modules: dict[str, Path]) -> str:
    return _dotted(modules[module])[1] if module in modules else module.rpartition(".")[0]


def _private_uses(path: Path, modules: dict[str, Path], top: Path = ROOT.parent
                  ) -> list[tuple[str, str, str]]:
    """(importer's package, imported module, private name) of every private name ``path``
    takes from another module: ``from m import _x``, ``from pkg import _module`` and
    ``m._x`` on a module ``m`` it imported."""
    name, package = _dotted(path, top)
    found, aliases = [], {}  # alias -> the module it names
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = (name if path.name == "__init__.py" else package).split(".")
                base = base[:len(base) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            for alias in node.names:
                sub = f"{target}.{alias.name}"
                if sub in modules:  # a module of a package
                    aliases[alias.asname or alias.name] = sub
                    if _private(alias.name):
                        found.append((package, target, alias.name))
                elif target in modules and _private(alias.name):
                    found.append((package, target, alias.name))
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name in modules:
                    aliases[alias.asname or alias.name] = alias.name
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and _private(node.attr):
            module = aliases.get(_dotted_name(node.value))
            if module is not None:
                found.append((package, module, node.attr))
    return found


def _dotted_name(node: ast.AST) -> str | None:
    """``a.b.c`` of a chain of attributes on a name, else None."""
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute):
        base = _dotted_name(node.value)
        return None if base is None else f"{base}.{node.attr}"
    return None


def _private_imports() -> tuple[list[str], list[str]]:
    """(uses across packages, uses within a package) of private names, as
    ``importer package: module._name``."""
    modules = _modules()
    across, within = set(), set()
    for path in modules.values():
        for package, target, private in _private_uses(path, modules):
            where = f"{path.relative_to(ROOT.parent)}: {target}.{private}"
            (within if _package_of(target, modules) == package else across).add(where)
    return sorted(across), sorted(within)


def test_no_private_name_taken_from_another_package():
    across, _ = _private_imports()
    assert across == []


def test_the_private_name_finder_finds_one(tmp_path):
    root = tmp_path / "workbook_gen"
    (root / "a").mkdir(parents=True)
    (root / "b").mkdir()
    for part in ("__init__.py", "a/__init__.py", "b/__init__.py", "b/inner.py"):
        (root / part).write_text("")
    (root / "a" / "m.py").write_text(
        "from workbook_gen.b.inner import _hidden, shown\n"
        "from ..b import inner\nfrom . import n\nfrom .n import _mine\n"
        "import workbook_gen.b.inner\n"
        "x = inner._other + n._same + workbook_gen.b.inner._dotted\n")
    (root / "a" / "n.py").write_text("")
    modules = {_dotted(p, tmp_path)[0]: p for p in root.rglob("*.py")}
    uses = _private_uses(root / "a" / "m.py", modules, tmp_path)
    assert sorted(uses) == [("workbook_gen.a", "workbook_gen.a.n", "_mine"),
                            ("workbook_gen.a", "workbook_gen.a.n", "_same"),
                            ("workbook_gen.a", "workbook_gen.b.inner", "_dotted"),
                            ("workbook_gen.a", "workbook_gen.b.inner", "_hidden"),
                            ("workbook_gen.a", "workbook_gen.b.inner", "_other")]
