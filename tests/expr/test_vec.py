"""expr/vec.py: vector and matrix trees evaluate to what numpy computes from the same
numbers (sums, dot and cross products, norms, matrix products, right-handed rotations
as scipy's Rotation gives them), and the builders fold literal zeros and ones without
changing a value."""

from __future__ import annotations

import random

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from workbook_gen import xlmath as xm
from workbook_gen.expr import Var
from workbook_gen.expr.excel import to_excel
from workbook_gen.expr.numeric import compile_numpy
from workbook_gen.expr.vec import (ONE, ZERO, add, combine, cross, dot, mat_mul, mat_vec,
                                   matrix_of, norm, rot_x, rot_y, rot_z, scale, sub, times,
                                   vec)

N = 40
RNG = np.random.default_rng(23)
NAMES = [f"v{i}" for i in range(12)]
DATA = {name: RNG.uniform(-3, 3, N) for name in NAMES}
COLUMNS = {name: xm.array(DATA[name]) for name in NAMES}


def value(tree) -> np.ndarray:
    out = compile_numpy(tree)(COLUMNS, {}, N)
    assert not out.err.any()
    return np.broadcast_to(out.val, (N,))


def tree_vec(i: int):
    return vec(Var(NAMES[i]), Var(NAMES[i + 1]), Var(NAMES[i + 2]))


def num_vec(i: int) -> np.ndarray:
    return np.stack([DATA[NAMES[i]], DATA[NAMES[i + 1]], DATA[NAMES[i + 2]]], axis=1)


def values(v) -> np.ndarray:
    return np.stack([value(x) for x in v], axis=1)


def test_vector_operations_as_numpy():
    u, w = tree_vec(0), tree_vec(3)
    nu, nw = num_vec(0), num_vec(3)
    k = Var(NAMES[6])
    nk = DATA[NAMES[6]][:, None]
    np.testing.assert_allclose(values(add(u, w)), nu + nw, rtol=1e-15)
    np.testing.assert_allclose(values(sub(u, w)), nu - nw, rtol=1e-15)
    np.testing.assert_allclose(values(scale(k, u)), nk * nu, rtol=1e-15)
    np.testing.assert_allclose(values(cross(u, w)), np.cross(nu, nw), rtol=1e-13, atol=1e-14)
    np.testing.assert_allclose(value(dot(u, w)), np.einsum("ij,ij->i", nu, nw), rtol=1e-13,
                               atol=1e-14)
    np.testing.assert_allclose(value(norm(u)), np.linalg.norm(nu, axis=1), rtol=1e-15)
    np.testing.assert_allclose(values(combine((k, u), (ONE, w))), nk * nu + nw, rtol=1e-14,
                               atol=1e-14)


def test_rotations_are_right_handed_and_compose_as_scipys():
    psi, theta, phi = Var("v0"), Var("v1"), Var("v2")
    q = mat_mul(rot_z(psi), mat_mul(rot_y(theta), rot_x(phi)))
    angles = np.stack([DATA["v0"], DATA["v1"], DATA["v2"]], axis=1)
    want = Rotation.from_euler("ZYX", angles).as_matrix()        # intrinsic z, y', x''
    got = np.stack([values(row) for row in q], axis=1)
    np.testing.assert_allclose(got, want, atol=1e-14)
    p = mat_vec(q, tree_vec(3))
    np.testing.assert_allclose(values(p), np.einsum("nij,nj->ni", want, num_vec(3)),
                               atol=1e-13)


def test_literal_zeros_and_ones_fold():
    x = Var("x")
    assert times(ZERO, x) == ZERO and times(ONE, x) == x
    same = str   # a quantity printed as its name
    assert to_excel(dot(vec(x, 0, 0), vec(1, Var("y"), Var("z"))), same) == "=x"
    assert [to_excel(c, same) for c in cross(vec(x, 0, 0), vec(0, Var("y"), 0))] == \
        ["=0", "=0", "=x*y"]
    assert to_excel(rot_z(x)[2][2], same) == "=1"
    assert matrix_of([Var(n) for n in NAMES[:9]])[2][1] == Var("v7")
    with pytest.raises(ValueError):
        matrix_of([x] * 8)
