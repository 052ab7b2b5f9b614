"""Parse Excel formula text into an AST by precedence climbing (Pratt parsing).

Excel's precedence, tightest first: unary ``-``/``+``, postfix ``%``, ``^`` (left
associative), ``* /``, ``+ -``, ``&``, comparisons. So ``-2^2`` is ``(-2)^2`` = 4 and
``2^3^2`` is ``(2^3)^2`` = 64. Ranges are single tokens (``A1:B3``, ``A:B``, ``2:3``,
``Sheet1:Sheet3!A1``); the reference operators bind tighter than any other: ``:``
between references that are not one token (``INDEX(..):INDEX(..)``), then the space
(intersection), then ``,`` (union, inside parentheses only). Array constants
(``{1,2;3,4}``) and structured references (``Table1[Amount]``) are single tokens.
"""

from __future__ import annotations

import re
from functools import lru_cache

from workbook_gen.errors import FormulaSyntaxError
from workbook_gen.formula import ast
from workbook_gen.formula import tokenizer as tk
from workbook_gen.xlerror import ExcelError

from workbook_gen.formula.ast import INFIX_POWER, PERCENT_POWER, PREFIX_POWER

RANGE_POWER, INTERSECT_POWER, UNION_POWER = 90, 85, 80
MAX_DEPTH = 128  # nesting of parentheses, functions and signs (Excel allows 64 functions)
_FUNC_PREFIXES = ("_xlfn._xlws.", "_xlfn.", "_xlws.")


@lru_cache(maxsize=8192)
def parse(formula: str) -> ast.Node:
    """The AST of ``formula`` (the leading ``=`` is optional).

    Trees are immutable, so the same text parsed again (by the grouping, the evaluator,
    the noise estimate and the checks of one audit, or the next workbook's audit in the
    same process) is the same tree, kept in a bounded cache.

    Raises FormulaSyntaxError with a message such as
    ``unexpected ')' at position 16 in '=SQRT(B2^2+C2^2))'``.
    """
    return _Parser(formula).parse()


@lru_cache(maxsize=4096)
def parse_name(text: str) -> ast.Node:
    """The AST of a defined name's text (the leading ``=`` is optional).  A name may
    refer to several areas joined by a top-level comma, the union operator there
    (``_xlnm.Print_Titles``: ``Table!$A:$A,Table!$1:$1``), which a cell's formula writes
    in parentheses: that reading is tried where the plain one fails on the comma.  The
    comma is Excel's union reference operator (Microsoft, "Calculation operators and
    precedence in Excel": ``, (comma)  Union operator, which combines multiple references
    into one reference``)."""
    text = str(text).lstrip("=")
    try:
        return parse(text)
    except FormulaSyntaxError as plain:
        if "," not in text:
            raise
        try:
            return parse(f"({text})")
        except FormulaSyntaxError:
            raise plain from None


class _Parser:
    def __init__(self, formula: str):
        self.text = formula
        self.tokens = tk.tokenize(formula)
        self.i = 0
        self.depth = 0

    # -- token access ----------------------------------------------------------------
    def _skip_ws(self) -> bool:
        skipped = False
        while self.i < len(self.tokens) and self.tokens[self.i].kind in (tk.WSPACE, tk.START):
            skipped = skipped or self.tokens[self.i].kind == tk.WSPACE
            self.i += 1
        return skipped

    def _peek(self) -> tk.Token | None:
        self._skip_ws()
        return self.tokens[self.i] if self.i < len(self.tokens) else None

    def _next(self) -> tk.Token | None:
        token = self._peek()
        self.i += 1
        return token

    def _fail(self, token: tk.Token | None, what: str | None = None) -> None:
        if token is None:
            raise FormulaSyntaxError(f"unexpected end of formula in '{self.text}'")
        raise FormulaSyntaxError(tk.describe(self.text, token.pos, what or f"unexpected {token.text!r}"))

    # -- grammar ---------------------------------------------------------------------
    def parse(self) -> ast.Node:
        if self._peek() is None:
            raise FormulaSyntaxError(f"empty formula '{self.text}'")
        node = self._expression(0)
        token = self._peek()
        if token is not None:
            self._fail(token)
        return node

    def _expression(self, min_power: int) -> ast.Node:
        self.depth += 1
        try:
            return self._climb(min_power)
        finally:
            self.depth -= 1

    def _climb(self, min_power: int) -> ast.Node:
        if self.depth > MAX_DEPTH:
            token = self._peek()
            raise FormulaSyntaxError(tk.describe(
                self.text, token.pos if token else len(self.text),
                f"formula nested deeper than {MAX_DEPTH} levels"))
        left = self._prefix()
        while True:
            token = self._peek()  # (it steps over white space: the space operator's)
            if token is None:
                return left
            had_space = self.tokens[self.i - 1].kind == tk.WSPACE
            if token.kind == tk.POSTFIX:
                if PERCENT_POWER < min_power:
                    return left
                self.i += 1
                left = ast.Percent(left)
            elif token.kind == tk.INFIX and token.text == "~":  # LibreOffice's union
                if UNION_POWER < min_power:
                    return left
                self.i += 1
                left = ast.RefOp("~", left, self._expression(UNION_POWER + 1))
            elif token.kind == tk.INFIX and token.text == ":":
                if RANGE_POWER < min_power:
                    return left
                self.i += 1
                left = ast.RefOp(":", left, self._expression(RANGE_POWER + 1))
            elif token.kind == tk.INFIX:
                power = INFIX_POWER[token.text]
                if power < min_power:
                    return left
                self.i += 1
                left = ast.Binary(token.text, left, self._expression(power + 1))
            elif had_space and token.kind in tk.OPERAND_KINDS | {tk.FUNC, tk.OPEN}:
                if INTERSECT_POWER < min_power:
                    return left
                left = ast.RefOp(" ", left, self._expression(INTERSECT_POWER + 1))
            else:
                return left

    def _prefix(self) -> ast.Node:
        token = self._next()
        if token is None:
            self._fail(None)
        kind = token.kind
        if kind == tk.PREFIX:
            return ast.Unary(token.text, self._expression(PREFIX_POWER))
        if kind == tk.OPEN:
            inner = self._expression(0)
            while (sep := self._peek()) is not None and sep.kind == tk.SEP:
                self.i += 1  # the union operator: (A1:A3,C1:C3)
                inner = ast.RefOp(",", inner, self._expression(0))
            self._expect_close(token)
            return ast.Paren(inner)
        if kind == tk.ARRAY:
            return _array(self.text, token)
        if kind == tk.STRUCT:
            table, _, spec = token.text.partition("[")
            return ast.StructRef(table, "[" + spec)
        if kind == tk.FUNC:
            return self._call(token)
        if kind == tk.NUMBER:
            return ast.Number(float(token.text), token.text)
        if kind == tk.STRING:
            return ast.String(token.text[1:-1].replace('""', '"'))
        if kind == tk.BOOL:
            return ast.Bool(token.text.upper() == "TRUE")
        if kind == tk.ERROR:
            # ('Sheet 1'!#REF!: the error after the sheet of a deleted reference)
            return ast.ErrorLit(ExcelError.from_text(token.text[token.text.rindex("#"):]))
        if kind == tk.REF:
            return self._reference(token)
        if kind == tk.NAME:
            sheet, name = tk.split_sheet(token.text)
            return ast.Name(name, None if sheet == "[0]" else sheet)
        self._fail(token)

    def _expect_close(self, opener: tk.Token) -> None:
        token = self._next()
        if token is None:
            raise FormulaSyntaxError(tk.describe(self.text, opener.pos, "unclosed '('"))
        if token.kind != tk.CLOSE:
            self._fail(token)

    def _call(self, token: tk.Token) -> ast.Func:
        full = token.text[:-1]
        prefix = ""
        for candidate in _FUNC_PREFIXES:
            if full.lower().startswith(candidate.lower()):
                prefix = full[:len(candidate)]
                break
        name = full[len(prefix):].upper()
        args: list[ast.Node] = []
        nxt = self._peek()
        if nxt is not None and nxt.kind == tk.CLOSE:
            self.i += 1
            return ast.Func(name, (), prefix)
        while True:
            nxt = self._peek()
            if nxt is not None and nxt.kind in (tk.SEP, tk.CLOSE):
                args.append(ast.Missing())
            else:
                args.append(self._expression(0))
            sep = self._next()
            if sep is None:
                raise FormulaSyntaxError(tk.describe(self.text, token.pos, f"unclosed '{token.text}'"))
            if sep.kind == tk.CLOSE:
                return ast.Func(name, tuple(args), prefix)
            if sep.kind != tk.SEP:
                self._fail(sep)

    def _reference(self, token: tk.Token) -> ast.Node:
        sheet, body = tk.split_sheet(token.text)
        sheet2 = None
        if sheet is not None and ":" in sheet:  # Excel forbids ':' in sheet names: 3-D
            sheet, _, sheet2 = sheet.partition(":")
        parts = body.split(":")
        cells = [_cell(p) for p in parts]
        if any(c is None for c in cells):
            cells = _whole(parts)
            if cells is None:
                self._fail(token, f"bad reference {token.text!r}")
            ref = ast.RangeRef(None if sheet2 else sheet, *cells)
        elif len(cells) == 1:
            ref = ast.CellRef(None if sheet2 else sheet, cells[0].col, cells[0].row,
                              cells[0].col_abs, cells[0].row_abs)
        else:
            ref = ast.RangeRef(None if sheet2 else sheet, cells[0], cells[1])
        return ast.Sheets3D(sheet, sheet2, ref) if sheet2 else ref


def _cell(text: str) -> ast.CellRef | None:
    m = tk.CELL_PARTS.fullmatch(text)
    if m is None:
        return None
    return ast.CellRef(None, tk.column_number(m.group(2)), int(m.group(4)),
                       col_abs=bool(m.group(1)), row_abs=bool(m.group(3)))


def _whole(parts: list[str]) -> tuple[ast.CellRef, ast.CellRef, str] | None:
    """The corners of ``A:B`` (every row) or ``2:3`` (every column), or None."""
    if len(parts) != 2:
        return None
    cols = [tk.WHOLE_COL.fullmatch(p) for p in parts]
    if all(cols):
        a, b = ((tk.column_number(m.group(2)), bool(m.group(1))) for m in cols)
        if max(a[0], b[0]) > ast.MAX_COL:
            return None
        return (ast.CellRef(None, a[0], 1, a[1], True),
                ast.CellRef(None, b[0], ast.MAX_ROW, b[1], True), "col")
    rows = [tk.WHOLE_ROW.fullmatch(p) for p in parts]
    if all(rows):
        a, b = ((int(m.group(2)), bool(m.group(1))) for m in rows)
        if not 1 <= min(a[0], b[0]) <= max(a[0], b[0]) <= ast.MAX_ROW:
            return None
        return (ast.CellRef(None, 1, a[0], True, a[1]),
                ast.CellRef(None, ast.MAX_COL, b[0], True, b[1]), "row")
    return None


_ITEM = re.compile(r'\s*(?:(?P<num>[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?)'
                   r'|(?P<str>"(?:[^"]|"")*")|(?P<bool>TRUE|FALSE)|(?P<err>#[A-Z0-9/_]+[!?]?|#N/A))'
                   r'\s*(?P<sep>[,;]|$)', re.IGNORECASE)


def _array(text: str, token: tk.Token) -> ast.Array:
    """``{1,2;3,"x"}``: rows separated by ';', items by ','; constants only."""
    inner = token.text[1:-1]
    rows: list[list[ast.Node]] = [[]]
    at = 0
    while True:
        m = _ITEM.match(inner, at)
        if m is None:
            raise FormulaSyntaxError(tk.describe(text, token.pos + 1 + at,
                                                 "an array constant holds only numbers, "
                                                 "text, TRUE/FALSE and errors"))
        if m.group("num"):
            rows[-1].append(ast.Number(float(m.group("num")), m.group("num")))
        elif m.group("str"):
            rows[-1].append(ast.String(m.group("str")[1:-1].replace('""', '"')))
        elif m.group("bool"):
            rows[-1].append(ast.Bool(m.group("bool").upper() == "TRUE"))
        else:
            error = ExcelError.from_text(m.group("err"))
            if error is None:
                raise FormulaSyntaxError(tk.describe(text, token.pos + 1 + at,
                                                     "unknown error literal"))
            rows[-1].append(ast.ErrorLit(error))
        at = m.end()
        if m.group("sep") == ";":
            rows.append([])
        elif not m.group("sep"):
            break
    if len({len(r) for r in rows}) != 1:
        raise FormulaSyntaxError(tk.describe(text, token.pos, "array constant rows differ "
                                                              "in length"))
    return ast.Array(tuple(tuple(r) for r in rows))
