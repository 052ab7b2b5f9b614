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
