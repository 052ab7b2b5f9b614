"""expr/tree.py: trees built with Python's operators evaluate as Python evaluates the same
expression (random trees, through the numpy printer); ``walk`` visits every node once,
parents first; ``variables``/``parameters`` are the names the tree holds; ``substitute``
is evaluation by parts (the substituted tree gives what the outer tree gives with the
inner tree's value); nodes are immutable, equal by structure, and hash alike."""

from __future__ import annotations

import dataclasses
import random

import numpy as np
import pytest

from workbook_gen import xlmath as xm
from workbook_gen.expr.numeric import compile_numpy
from workbook_gen.expr.tree import Bin, Neg, Num, Param, Var, parameters, substitute, variables, walk

NAMES = ["a", "b", "c"]
PARAMS = {"p": 1.5, "q": -0.25}


def random_tree(rng: random.Random, depth: int):
    """(tree, the same expression as a Python function of (values, params))."""
    if depth == 0 or rng.random() < 0.25:
        kind = rng.choice(["var", "param", "num"])
        if kind == "var":
            name = rng.choice(NAMES)
            return Var(name), lambda v, p, n=name: v[n]
        if kind == "param":
            name = rng.choice(list(PARAMS))
            return Param(name), lambda v, p, n=name: p[n]
        k = float(rng.randint(1, 9))
        return Num(k), lambda v, p, k=k: k
    op = rng.choice(["+", "-", "*", "neg"])
    left, f = random_tree(rng, depth - 1)
    if op == "neg":
        return -left, lambda v, p, f=f: -f(v, p)
    right, g = random_tree(rng, depth - 1)
    if op == "+":
        return left + right, lambda v, p, f=f, g=g: f(v, p) + g(v, p)
    if op == "-":
        return left - right, lambda v, p, f=f, g=g: f(v, p) - g(v, p)
    return left * right, lambda v, p, f=f, g=g: f(v, p) * g(v, p)


def value(tree, values: dict) -> float:
    columns = {k: xm.array(np.array([v])) for k, v in values.items()}
    out = compile_numpy(tree)(columns, PARAMS, 1)
    return float(np.broadcast_to(out.val, (1,))[0])


@pytest.mark.parametrize("seed", range(40))
def test_operators_walk_names_and_substitution(seed):
    rng = random.Random(seed)
    tree, fn = random_tree(rng, 5)
    values = {n: rng.uniform(-3, 3) for n in NAMES}
    assert value(tree, values) == pytest.approx(fn(values, PARAMS), rel=1e-12, abs=1e-12)
    nodes = list(walk(tree))
    assert nodes[0] is tree and len(nodes) == len({id(n) for n in nodes})
    assert variables(tree) == {n.name for n in nodes if isinstance(n, Var)}
    assert parameters(tree) == {n.name for n in nodes if isinstance(n, Param)}
    inner, g = random_tree(rng, 3)
    replaced = substitute(tree, {"a": inner})
    assert "a" not in variables(replaced) or "a" in variables(inner)
    by_parts = dict(values, a=g(values, PARAMS))
    assert value(replaced, values) == pytest.approx(fn(by_parts, PARAMS), rel=1e-10,
                                                    abs=1e-10)


def test_nodes_are_immutable_equal_by_structure_and_hash_alike():
    x = Var("x")
    t1, t2 = (x + 1) * Param("k"), (Var("x") + 1) * Param("k")
    assert t1 == t2 and hash(t1) == hash(t2) and t1 is not t2
    assert t1 != (x + 2) * Param("k")
    assert (2 - x) == Bin("-", Num(2.0), x) and -x == Neg(x)
    with pytest.raises(dataclasses.FrozenInstanceError):
        x.name = "y"
