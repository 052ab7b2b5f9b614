"""Expression trees (one per quantity) and their printers."""

from .build import (abs_, acos, and_, asin, atan, atan2, concat, cos, degrees, eq, ge, gt,
                    if_, iferror, iserror, le, lt, max_, min_, mod, ne, not_, or_, pi, power,
                    radians, root, sign, sin, sqrt, tan)
from .tree import (Bin, Call, Neg, Node, Num, Param, Text, Var, parameters, substitute,
                   variables, walk, wrap)

__all__ = [
    "Bin", "Call", "Neg", "Node", "Num", "Param", "Text", "Var", "parameters", "substitute",
    "variables", "walk", "wrap", "abs_", "acos", "and_", "asin", "atan", "atan2", "concat",
    "cos", "degrees", "eq", "ge", "gt", "if_", "iferror", "iserror", "le", "lt", "max_",
    "min_", "mod", "ne", "not_", "or_", "pi", "power", "radians", "root", "sign", "sin",
    "sqrt", "tan",
]
