"""The functions a formula calls, as the engine decides what it can check.

- :func:`unsupported`: those the evaluator lacks, and those the application lacks (a
  future function stored without its ``_xlfn.`` prefix, in Excel); a defined name holding
  a LAMBDA, called by name, is not one of them (its body's calls are looked into);
- :func:`unknown_reason`: a formula whose unsupported calls are all of names unknown to
  the application (:mod:`formula.functions.availability`): ``#NAME?`` in Excel, unless
  an add-in or the workbook's macros define them;
- :func:`guarded` and :func:`avoids`: an unsupported call inside a lazy function's
  branch (IF, IFERROR, CHOOSE ...) that the cell's evaluation does not take, as Excel
  does not evaluate it either: the cell's value does not depend on it.
"""

from __future__ import annotations

from workbook_gen.evaluator.store import Names, SheetResolver, Store
from workbook_gen.formula import ast
from workbook_gen.formula import functions as fx
from workbook_gen.formula.functions import availability
from workbook_gen.formula.scalar import evaluate, unsupported_functions

MAX_LAMBDA_DEPTH = 8  # named LAMBDAs calling named LAMBDAs, looked into


def _lambda_of(names: Names, name: str, sheet: str) -> ast.Func | None:
    tree = names.node(name, None, sheet)
    while isinstance(tree, ast.Paren):
        tree = tree.inner
    return tree if isinstance(tree, ast.Func) and tree.name == "LAMBDA" else None


def unsupported(node: ast.Node, names: Names, sheet: str, dialect: str, stored: bool,
                depth: int = 0) -> set[str]:
    """The names of the functions ``node`` calls that cannot be evaluated (see above);
    ``stored``: the formula is as a file stores it."""
    out = {n.name for n in ast.walk(node) if isinstance(n, ast.Func)
           and availability.unavailable(n.name, n.prefix, dialect, stored)}
    for name in unsupported_functions(node):
        body = _lambda_of(names, name, sheet)
        if body is not None and depth < MAX_LAMBDA_DEPTH:
            out |= unsupported(body, names, sheet, dialect, stored, depth + 1) - {name}
        else:
            out.add(name)
    return out


def unknown_reason(node: ast.Node, bad: list[str], dialect: str, stored: bool) -> str | None:
    """Why a formula whose unsupported calls (``bad``) are all of names the application
    does not know is not checked, or None if some call is of a function it knows."""
    bare = {n.name for n in ast.walk(node) if isinstance(n, ast.Func)
            and availability.unavailable(n.name, n.prefix, dialect, stored)}
    if not bad or not all(n in bare or not availability.known(n, fx.SUPPORTED) for n in bad):
        return None
    listed = ", ".join(f"{n} (stored without its _xlfn. prefix)" if n in bare else n
                       for n in bad)
    return f"unknown function {listed}: #NAME? unless an add-in or a macro defines it"


def bare_future(node: ast.Node) -> bool:
    """Does the formula name a future function without its prefix?"""
    return any(isinstance(n, ast.Func) and not n.prefix and n.name in availability.FUTURE
               for n in ast.walk(node))


def guarded(node: ast.Node) -> bool:
    """Does the formula call a function that may be unsupported inside a lazy one, so
    that a cell may take a branch without it?"""
    funcs = [n for n in ast.walk(node) if isinstance(n, ast.Func)]
    return (any(n.name in fx.LAZY for n in funcs)
            and any(n.name not in fx.REGISTRY or (not n.prefix and n.name in
                                                   availability.FUTURE) for n in funcs))


def avoids(node: ast.Node, cell: tuple[str, int, int], store: Store, names: Names,
           dialect: str) -> bool:
    """Does the cell's evaluation reach no unsupported function (its value then does not
    depend on one)? The cells it reads are in ``store`` already."""
    reached: list[str] = []
    try:
        evaluate(node, SheetResolver(store, names, cell[0]), dialect=dialect,
                 on_unsupported=reached.append, cell=cell)
    except (ArithmeticError, ValueError, TypeError, IndexError, KeyError,
            AttributeError, RecursionError):
        return False
    return not reached
