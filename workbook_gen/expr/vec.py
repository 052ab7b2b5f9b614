"""3-vectors and 3x3 matrices of trees: sums, products, dot and cross, rotations.

A vector is a tuple of three trees, a matrix a tuple of three rows.  The
builders fold literal zeros and ones as they go, so that a product of
elementary rotations prints as the familiar entries (``COS(psi)*COS(theta)``),
not as sums of ``0*...`` terms; nothing else is simplified, so each entry is
the tree one would write by hand.

    Q = mat_mul(rot_z(psi), mat_mul(rot_y(theta), rot_x(phi)))
    p = add(p5, mat_vec(Q, sub(a, a5)))
"""

from __future__ import annotations

from .build import cos, sin, sqrt
from .tree import Neg, Node, Num, Operand, wrap

Vec3 = tuple[Node, Node, Node]
Mat3 = tuple[Vec3, Vec3, Vec3]

ZERO, ONE = Num(0.0), Num(1.0)


def is_zero(node: Operand) -> bool:
    n = wrap(node)
    return n == ZERO or (isinstance(n, Neg) and n.operand == ZERO)


def is_one(node: Operand) -> bool:
    return wrap(node) == ONE


def plus(a: Operand, b: Operand) -> Node:
    """a + b without literal zeros; a + (-x) is written a - x."""
    a, b = wrap(a), wrap(b)
    if is_zero(a):
        return b
    if is_zero(b):
        return a
    if isinstance(b, Neg):
        return a - b.operand
    return a + b


def minus(a: Operand, b: Operand) -> Node:
    """a - b without literal zeros; a - (-x) is written a + x."""
    a, b = wrap(a), wrap(b)
    if is_zero(b):
        return a
    if is_zero(a):
        return negate(b)
    if isinstance(b, Neg):
        return a + b.operand
    return a - b


def negate(a: Operand) -> Node:
    a = wrap(a)
    if is_zero(a):
        return ZERO
    return a.operand if isinstance(a, Neg) else Neg(a)


def times(a: Operand, b: Operand) -> Node:
    """a * b with 0 and 1 folded and a sign pulled out: (-x)*y is -(x*y)."""
    a, b = wrap(a), wrap(b)
    if is_zero(a) or is_zero(b):
        return ZERO
    if is_one(a):
        return b
    if is_one(b):
        return a
    if isinstance(a, Neg) and isinstance(b, Neg):
        return times(a.operand, b.operand)
    if isinstance(a, Neg):
        return negate(times(a.operand, b))
    if isinstance(b, Neg):
        return negate(times(a, b.operand))
    return a * b


def total(terms: list[Operand]) -> Node:
    """The sum of ``terms`` left to right, literal zeros dropped (0 if none is left)."""
    out: Node = ZERO
    for term in terms:
        out = plus(out, term)
    return out


def vec(x: Operand, y: Operand, z: Operand) -> Vec3:
    return (wrap(x), wrap(y), wrap(z))


def add(u: Vec3, w: Vec3) -> Vec3:
    return (plus(u[0], w[0]), plus(u[1], w[1]), plus(u[2], w[2]))


def sub(u: Vec3, w: Vec3) -> Vec3:
    return (minus(u[0], w[0]), minus(u[1], w[1]), minus(u[2], w[2]))


def scale(k: Operand, u: Vec3) -> Vec3:
    return (times(k, u[0]), times(k, u[1]), times(k, u[2]))


def combine(*terms: tuple[Operand, Vec3]) -> Vec3:
    """sum k_j u_j over (k_j, u_j) pairs."""
    return tuple(total([times(k, u[i]) for k, u in terms]) for i in range(3))  # type: ignore[return-value]


def dot(u: Vec3, w: Vec3) -> Node:
    return total([times(u[i], w[i]) for i in range(3)])


def cross(u: Vec3, w: Vec3) -> Vec3:
    return (minus(times(u[1], w[2]), times(u[2], w[1])),
            minus(times(u[2], w[0]), times(u[0], w[2])),
            minus(times(u[0], w[1]), times(u[1], w[0])))


def norm(u: Vec3) -> Node:
    return sqrt(total([u[i] ** 2 for i in range(3) if not is_zero(u[i])]))


def mat_vec(m: Mat3, u: Vec3) -> Vec3:
    return (dot(m[0], u), dot(m[1], u), dot(m[2], u))


def column(m: Mat3, j: int) -> Vec3:
    return (m[0][j], m[1][j], m[2][j])


def mat_mul(a: Mat3, b: Mat3) -> Mat3:
    cols = [column(b, j) for j in range(3)]
    return tuple(tuple(dot(a[i], cols[j]) for j in range(3))  # type: ignore[return-value]
                 for i in range(3))


def rot_x(angle: Operand) -> Mat3:
    """Rotation about x by ``angle`` (radians), right-handed."""
    c, s = cos(angle), sin(angle)
    return ((ONE, ZERO, ZERO), (ZERO, c, Neg(s)), (ZERO, s, c))


def rot_y(angle: Operand) -> Mat3:
    c, s = cos(angle), sin(angle)
    return ((c, ZERO, s), (ZERO, ONE, ZERO), (Neg(s), ZERO, c))


def rot_z(angle: Operand) -> Mat3:
    c, s = cos(angle), sin(angle)
    return ((c, Neg(s), ZERO), (s, c, ZERO), (ZERO, ZERO, ONE))


def matrix_of(entries: list[Node]) -> Mat3:
    """A matrix from nine trees, row by row (e.g. the Vars of nine Table columns)."""
    if len(entries) != 9:
        raise ValueError(f"a 3x3 matrix needs 9 entries, got {len(entries)}")
    return tuple(tuple(entries[3 * i:3 * i + 3]) for i in range(3))  # type: ignore[return-value]
