"""Excel's formula language: tokenizer, parser, AST, printer and a scalar evaluator.

    node = parse("=IF(A2>0,SQRT(A2),#NUM!)")
    render(node)                      # 'IF(A2>0,SQRT(A2),#NUM!)' (no leading '=')
    to_relative(node, 2, 3)           # 'IF(RC[-2]>0,SQRT(RC[-2]),#NUM!)'
    evaluate(node, DictResolver({"A2": 4.0}))   # 2.0
"""

from workbook_gen.formula.ast import (
    Binary, Bool, CellRef, ErrorLit, Func, Missing, Name, Node, Number, Paren, Percent,
    RangeRef, String, Unary, shift, walk,
)
from workbook_gen.formula.functions import (
    LIBREOFFICE_DIFFERENCES, SUPPORTED, Difference, libreoffice_result,
)
from workbook_gen.formula import arrays as _arrays  # noqa: F401  (registers array evaluation)
from workbook_gen.formula.parser import parse
from workbook_gen.formula.printer import (column_letters, quote_sheet, render, render_formula,
                                         to_relative)
from workbook_gen.formula.scalar import DictResolver, Resolver, evaluate, unsupported_functions
from workbook_gen.formula.tokenizer import Token, Tokenizer, is_cell_ref, tokenize
from workbook_gen.formula.values import Range, Value

__all__ = [
    "Binary", "Bool", "CellRef", "ErrorLit", "Func", "Missing", "Name", "Node", "Number",
    "Paren", "Percent", "RangeRef", "String", "Unary", "shift", "to_relative", "walk",
    "LIBREOFFICE_DIFFERENCES", "SUPPORTED", "Difference", "Range", "Value",
    "libreoffice_result", "parse", "column_letters", "quote_sheet", "render",
    "render_formula", "DictResolver", "Resolver", "evaluate", "unsupported_functions",
    "Token", "Tokenizer", "is_cell_ref", "tokenize",
]
