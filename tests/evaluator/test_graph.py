"""evaluator/graph.py's ``order``: the strongly connected components of the dependency
graph, each after every component it reads, against a brute-force reference (two units
share a component exactly when each reaches the other), on random graphs; and
``is_cycle``: a component of several units, or one that reads itself."""

from __future__ import annotations

import random

import pytest

from workbook_gen.evaluator.graph import is_cycle, order


def reach(deps: list[list[int]]) -> list[set[int]]:
    """reach[v]: every unit v reads, directly or not (v itself only through a cycle)."""
    out = []
    for v in range(len(deps)):
        seen, todo = set(), list(deps[v])
        while todo:
            w = todo.pop()
            if w not in seen:
                seen.add(w)
                todo.extend(deps[w])
        out.append(seen)
    return out


def random_graph(rng: random.Random) -> list[list[int]]:
    n = rng.randint(1, 40)
    density = rng.choice([0.02, 0.05, 0.1, 0.3])
    return [sorted({w for w in range(n) if rng.random() < density}) for _ in range(n)]


@pytest.mark.parametrize("seed", range(60))
def test_components_and_their_order(seed):
    deps = random_graph(random.Random(seed))
    components = order(deps)
    flat = [v for c in components for v in c]
    assert sorted(flat) == list(range(len(deps)))          # each unit once
    where = {v: i for i, c in enumerate(components) for v in c}
    r = reach(deps)
    for v in range(len(deps)):
        for w in range(len(deps)):
            same = v == w or (w in r[v] and v in r[w])
            assert (where[v] == where[w]) == same, (v, w)
        for w in deps[v]:
            assert where[w] <= where[v], (v, w)              # what v reads comes first
    for c in components:
        assert is_cycle(c, deps) == (c[0] in r[c[0]])


def test_a_self_reference_is_a_cycle_and_a_chain_is_not():
    deps = [[1], [2], [], [3]]
    assert order(deps)[:3] == [[2], [1], [0]]
    assert [is_cycle(c, deps) for c in order(deps)] == [False, False, False, True]


def test_a_long_chain_needs_no_recursion():
    n = 50_000   # far beyond Python's recursion limit
    deps = [[i + 1] for i in range(n - 1)] + [[]]
    assert order(deps) == [[i] for i in reversed(range(n))]
